!> What a finished sweep reports: the sensitivities of every summary output
!! to every parameter, a paged listing (parameters, one row per member run,
!! failed runs with their messages, the sensitivity table) and one HDF5
!! file with the inputs and outputs of every run. Layout in docs/sweeps.md.
module hn_sweep_report
    use hn_kinds, only: wp, zero, msglen
    use hn_sweep, only: sweep_t, member_record_t, output_names, output_units, output_ref, output_group, nout, &
                        design_name, design_oat, design_factorial, design_lhs, par_family, par_body
    use hn_sensitivity, only: oat_sensitivity, regression_sensitivity, roundoff_outputs
    use hn_listing, only: listing_t
    use hn_h5, only: h5_file_t
    use hn_deck_reader, only: int_str
    implicit none
    private

    public :: sweep_finish, sweep_sensitivities, param_label

    !> Version of the sweep file's layout (root attribute schema_version;
    !! the rules for changing it in docs/output-format.md).
    integer, parameter :: sweep_schema_version = 2

    !> Outputs shown in the listing's run and sensitivity tables: the
    !! sagittal ones, the 3-D and out-of-plane ones (eight each, so that
    !! a table fits the 118 columns of the listing page), then the
    !! rear-impact ones (head extension relative to T1 and when, NIC, the
    !! upper-neck extension moment and fore-aft shear, first contact).
    integer, parameter :: shown_sagittal(8) = [1, 2, 4, 6, 8, 9, 10, 12]
    integer, parameter :: shown_3d(8) = [14, 16, 17, 21, 22, 24, 26, 27]
    integer, parameter :: shown_rear(6) = [29, 30, 13, 10, 23, 31]
    integer, parameter :: max_shown_params = 9   !! parameter columns of the member table
    integer, parameter :: col = 13               !! width of an output column

    !> A finished sweep: what the listing and the result file report.
    type :: sweep_outcome_t
        real(wp), allocatable :: v(:, :)                !! (np, nrun) design: parameter values of every member
        type(member_record_t), allocatable :: recs(:)   !! (nrun) what each member run gave
        real(wp), allocatable :: s(:, :)                !! (np, nout) sensitivities
        logical, allocatable :: valid(:, :)             !! (np, nout) s could be computed
        logical, allocatable :: roundoff(:)             !! (nout) the output is roundoff in every member
        real(wp), allocatable :: r2(:)                  !! (nout) R^2 of each output's regression
        integer :: nranks = 1                           !! number of MPI ranks that ran the members
        real(wp) :: wall = zero                         !! wall time of the whole sweep [s]
    end type sweep_outcome_t

contains

    !> Everything after the member runs: sensitivities, the listing on unit
    !! lu, and the result file `h5name` ('' for none).
    subroutine sweep_finish(sw, v, recs, nranks, wall, lu, h5name, version, stat, errmsg)
        type(sweep_t), intent(in) :: sw                !! the sweep
        real(wp), intent(in) :: v(:, :)                !! (np, nrun) design: parameter values of every member
        type(member_record_t), intent(in) :: recs(:)   !! (nrun) what each member run gave
        integer, intent(in) :: nranks                  !! number of MPI ranks that ran the members
        integer, intent(in) :: lu                      !! unit of the sweep listing
        real(wp), intent(in) :: wall                   !! wall time of the whole sweep [s]
        character(len=*), intent(in) :: h5name         !! sweep result file ('' for none)
        character(len=*), intent(in) :: version        !! program version for the listing and the file
        integer, intent(out) :: stat                   !! stat_ok, or the failure to write the result file
        character(len=msglen), intent(out) :: errmsg   !! why the file could not be written ('' when stat_ok)
        type(sweep_outcome_t) :: o
        o%v = v
        o%recs = recs
        o%nranks = nranks
        o%wall = wall
        allocate (o%s(size(v, 1), nout), o%valid(size(v, 1), nout), o%r2(nout), o%roundoff(nout))
        call sweep_sensitivities(sw, v, recs, o%s, o%valid, o%r2, o%roundoff)
        call sweep_listing(sw, o, lu, version)
        stat = 0
        errmsg = ''
        if (len(h5name) > 0) call sweep_write_h5(sw, o, h5name, version, stat, errmsg)
    end subroutine sweep_finish

    !> Sensitivity s(p, k) of output k to parameter p (elasticities for OAT,
    !! standardised regression coefficients otherwise), their validity, and
    !! R^2 of each regression (1 for OAT). An output that is roundoff in every
    !! completed member (hn_sensitivity's roundoff_outputs) has none: s = 0,
    !! valid false, R^2 = 0.
    subroutine sweep_sensitivities(sw, v, recs, s, valid, r2, roundoff)
        type(sweep_t), intent(in) :: sw                   !! the sweep (design, step, LOG spacing)
        real(wp), intent(in) :: v(:, :)                   !! (np, nrun) design
        type(member_record_t), intent(in) :: recs(:)      !! (nrun) status and summary outputs of every member
        real(wp), intent(out) :: s(size(v, 1), nout)      !! sensitivity of output k to parameter p
        logical, intent(out) :: valid(size(v, 1), nout)   !! s(p, k) could be computed
        real(wp), intent(out) :: r2(nout)                 !! R^2 of each output's regression (1 for OAT)
        logical, intent(out), optional :: roundoff(nout)  !! the output is roundoff in every completed member
        real(wp) :: x(size(v, 1), size(v, 2))
        logical :: ok(size(recs)), noise(nout)
        real(wp) :: y(size(recs)), outs(nout, size(recs))
        integer :: k, p
        ok = recs%status == 0
        do k = 1, size(recs)
            outs(:, k) = recs(k)%outputs
        end do
        noise = roundoff_outputs(outs, ok, output_ref, output_group)
        if (sw%design == design_oat) then
            r2 = 1.0_wp
            do k = 1, nout
                y = recs%outputs(k)
                call oat_sensitivity(y, ok, sw%percent, s(:, k), valid(:, k))
            end do
        else
            x = v
            do p = 1, size(v, 1)
                if (sw%params(p)%log_spacing) x(p, :) = log(v(p, :))
            end do
            do k = 1, nout
                y = recs%outputs(k)
                call regression_sensitivity(x, y, ok, s(:, k), r2(k), valid(1, k))
                valid(:, k) = valid(1, k)
            end do
        end if
        do k = 1, nout
            if (.not. noise(k)) cycle
            s(:, k) = zero
            valid(:, k) = .false.
            r2(k) = zero
        end do
        if (present(roundoff)) roundoff = noise
    end subroutine sweep_sensitivities

    !> "FAMILY MUSCLES M1", "BODY HEAD MASS", "DISC C2C1 F5".
    pure function param_label(sw, p) result(s)
        type(sweep_t), intent(in) :: sw   !! the sweep
        integer, intent(in) :: p          !! parameter number
        character(len=32) :: s
        associate (q => sw%params(p))
            select case (q%kind)
            case (par_family); s = 'FAMILY '//trim(q%target)//' '//trim(q%item)
            case (par_body); s = 'BODY '//trim(q%target)//' '//trim(q%item)
            case default; s = trim(q%target)//' '//trim(q%item)//' F'//trim(int_str(q%field))
            end select
        end associate
    end function param_label

    !> Units of parameter p's values: '1' for a FAMILY or BODY scale
    !! factor, 'units of CARD Fn' for a FIELD parameter (the value is in
    !! that deck field's own units, docs/deck-format.md).
    pure function param_units(sw, p) result(s)
        type(sweep_t), intent(in) :: sw   !! the sweep
        integer, intent(in) :: p          !! parameter number
        character(len=32) :: s
        associate (q => sw%params(p))
            select case (q%kind)
            case (par_family, par_body); s = '1'
            case default; s = 'units of '//trim(q%target)//' F'//trim(int_str(q%field))
            end select
        end associate
    end function param_units

    !> The sweep listing on unit lu: the deck's echo, the sweep and its
    !! parameters, the member runs, their outputs, the sensitivities and
    !! the most influential parameter per output.
    subroutine sweep_listing(sw, o, lu, version)
        type(sweep_t), intent(in) :: sw                !! the sweep
        type(sweep_outcome_t), intent(in) :: o         !! design, member records, sensitivities, ranks, wall time
        integer, intent(in) :: lu                      !! unit of the sweep listing
        character(len=*), intent(in) :: version        !! program version for the page headers
        type(listing_t) :: lst
        integer :: nrun, nfail
        nrun = size(o%v, 2)
        nfail = count(o%recs%status /= 0)
        call lst%start(lu, 'SWEEP: '//sw%title, version)
        call lst%echo_deck(sw%deck)
        call lst%new_page()
        call listing_parameters(lst, sw, o)
        call listing_members(lst, sw, o)
        call output_table(lst, o, ' MEMBER RUNS: SAGITTAL OUTPUTS (head rotation and angular motion about y, upper-neck '// &
                          'Fx, Fz, My)', shown_sagittal)
        call output_table(lst, o, ' MEMBER RUNS: 3-D AND OUT-OF-PLANE OUTPUTS (Bryant angles x, z and total angle; '// &
                          'resultants; Fy, Mx, Mz)', shown_3d)
        call output_table(lst, o, ' MEMBER RUNS: REAR-IMPACT OUTPUTS (head extension relative to T1, NIC, '// &
                          'upper-neck My and Fx, first contact)', shown_rear)
        ! the sensitivity tables
        call sensitivity_table(lst, sw, o, ' SAGITTAL OUTPUTS', shown_sagittal)
        call sensitivity_table(lst, sw, o, ' 3-D AND OUT-OF-PLANE OUTPUTS', shown_3d)
        call sensitivity_table(lst, sw, o, ' REAR-IMPACT OUTPUTS', shown_rear)
        call influence_table(lst, sw, o)
        if (nfail > 0) call lst%message(trim(int_str(nfail))//' OF '//trim(int_str(nrun))// &
                                        ' MEMBER RUNS FAILED; SEE THE LIST ABOVE')
    end subroutine sweep_listing

    !> The sweep's page: base deck, design, runs, and the parameters' table.
    subroutine listing_parameters(lst, sw, o)
        type(listing_t), intent(inout) :: lst          !! the sweep listing
        type(sweep_t), intent(in) :: sw                !! the sweep
        type(sweep_outcome_t), intent(in) :: o         !! design, member records, ranks, wall time
        character(len=400) :: line
        integer :: p, nrun, nfail
        nrun = size(o%v, 2)
        nfail = count(o%recs%status /= 0)
        call lst%put(' PARAMETER SWEEP')
        call lst%put('')
        call lst%put('   base deck       '//trim(sw%base))
        select case (sw%design)
        case (design_oat)
            write (line, '(a,f8.3,a)') '   design          OAT: run 1 nominal, then each parameter at -/+', &
                sw%percent, ' % (normalised sensitivities)'
        case default
            line = '   design          '//trim(design_name(sw%design))
            if (sw%levels > 0 .and. sw%design == design_factorial) line = trim(line)//', '//trim(int_str(sw%levels))// &
                                                           ' levels per parameter'
            if (sw%design == design_lhs) line = trim(line)//', seed '//trim(int_str(sw%seed))
            line = trim(line)//' (standardised regression coefficients)'
        end select
        call lst%put(line)
        write (line, '(a,i0,a,i0,a,i0,a,f10.2,a,f8.3,a)') '   runs            ', nrun, ' (', nrun - nfail, &
            ' complete, ', nfail, ' failed) on ', real(o%nranks, wp), ' ranks, ', o%wall, ' s wall time'
        call lst%put(line)
        call lst%put('')
        call lst%put('   NO  NAME        WHAT                              LOW           HIGH          NOMINAL   SPACING')
        do p = 1, size(o%v, 1)
            associate (q => sw%params(p))
                write (line, '(i5,2x,a10,2x,a32,3es14.5,2x,a)') p, q%name, param_label(sw, p), q%low, q%high, &
                    q%nominal, merge('LOG', 'LIN', q%log_spacing)
                if (sw%design == design_oat) write (line, '(i5,2x,a10,2x,a32,28x,es14.5,2x,a)') p, q%name, &
                    param_label(sw, p), q%nominal, 'OAT'
            end associate
            call lst%put(line)
        end do
    end subroutine listing_parameters

    !> The members' parameter values (the first max_shown_params), then the
    !! failed runs with their exit codes and messages.
    subroutine listing_members(lst, sw, o)
        type(listing_t), intent(inout) :: lst          !! the sweep listing
        type(sweep_t), intent(in) :: sw                !! the sweep
        type(sweep_outcome_t), intent(in) :: o         !! design and member records
        character(len=400) :: line
        integer :: p, r, np, nrun, nfail
        np = size(o%v, 1)
        nrun = size(o%v, 2)
        nfail = count(o%recs%status /= 0)
        call lst%new_page()
        call lst%put(' MEMBER RUNS: PARAMETER VALUES (FAMILY and BODY parameters as scale factors, FIELD parameters '// &
                     'as values)')
        if (np > max_shown_params) call lst%put(' (the first '//trim(int_str(max_shown_params))// &
                                                ' parameters are shown; every input and output is in the HDF5 file)')
        call lst%put('')
        line = '   RUN ST'
        do p = 1, min(np, max_shown_params)
            line = trim(line)//'  '//adjustr(sw%params(p)%name)
        end do
        call lst%put(line)
        do r = 1, nrun
            write (line, '(i6,i3)') r, o%recs(r)%status
            do p = 1, min(np, max_shown_params)
                write (line(len_trim(line) + 1:), '(2x,es10.3)') o%v(p, r)
            end do
            if (o%recs(r)%status /= 0) line = trim(line)//'  FAILED (below)'
            call lst%put(line)
        end do
        if (nfail > 0) then
            call lst%put('')
            call lst%put(' FAILED RUNS (exit code and message; they are excluded from the sensitivities)')
            do r = 1, nrun
                if (o%recs(r)%status == 0) cycle
                write (line, '(a,i0,a,i0,a)') '   run ', r, ' (exit ', o%recs(r)%status, '): '
                call lst%put(trim(line)//' '//trim(o%recs(r)%message))
            end do
        end if
    end subroutine listing_members

    !> The most influential parameter of every output (the largest
    !! sensitivity in magnitude), or why there is none.
    subroutine influence_table(lst, sw, o)
        type(listing_t), intent(inout) :: lst          !! the sweep listing
        type(sweep_t), intent(in) :: sw                !! the sweep
        type(sweep_outcome_t), intent(in) :: o         !! sensitivities, their validity, roundoff outputs
        character(len=400) :: line
        integer :: p, k
        call lst%need(3 + nout)
        call lst%put('')
        call lst%put(' MOST INFLUENTIAL PARAMETER PER OUTPUT (every output; n/a: no sensitivity could be computed)')
        do k = 1, nout
            if (any(o%valid(:, k))) then
                p = maxloc(abs(o%s(:, k)), mask=o%valid(:, k), dim=1)
                write (line, '(3x,a12,1x,a8,2x,a10,f10.3)') output_names(k), output_units(k), sw%params(p)%name, &
                    o%s(p, k)
            else if (o%roundoff(k)) then
                write (line, '(3x,a12,1x,a8,2x,a)') output_names(k), output_units(k), &
                    'n/a: roundoff in every member (below 1E-8 of its group)'
            else
                write (line, '(3x,a12,1x,a8,2x,a)') output_names(k), output_units(k), 'n/a'
            end if
            call lst%put(line)
        end do
    end subroutine influence_table

    !> One row per member of the outputs `which`, under its title.
    subroutine output_table(lst, o, title, which)
        type(listing_t), intent(inout) :: lst          !! the sweep listing
        type(sweep_outcome_t), intent(in) :: o         !! member records
        character(len=*), intent(in) :: title          !! the table's title
        integer, intent(in) :: which(:)                !! the outputs shown
        character(len=400) :: line
        integer :: j, r
        real(wp) :: x
        call lst%need(6 + min(size(o%recs), 10))
        call lst%put('')
        call lst%put(title)
        call lst%put('')
        line = '   RUN ST'
        do j = 1, size(which)
            line(10 + col*(j - 1):) = ' '//adjustr(output_names(which(j)))
        end do
        call lst%put(line)
        line = ''
        do j = 1, size(which)
            line(10 + col*(j - 1):) = repeat(' ', col - 8)//adjustr(output_units(which(j)))
        end do
        call lst%put(line)
        do r = 1, size(o%recs)
            write (line, '(i6,i3)') r, o%recs(r)%status
            if (o%recs(r)%status == 0) then
                do j = 1, size(which)
                    x = o%recs(r)%outputs(which(j))
                    write (line(10 + col*(j - 1):), '(1x,g12.4)') merge(zero, x, x == zero)   ! -0 as 0
                end do
            else
                line = trim(line)//'  failed'
            end if
            call lst%put(line)
        end do
    end subroutine output_table

    !> The sensitivities of the outputs `which` to every parameter.
    subroutine sensitivity_table(lst, sw, o, title, which)
        type(listing_t), intent(inout) :: lst          !! the sweep listing
        type(sweep_t), intent(in) :: sw                !! the sweep
        type(sweep_outcome_t), intent(in) :: o         !! sensitivities, their validity, R^2
        character(len=*), intent(in) :: title          !! the table's title
        integer, intent(in) :: which(:)                !! the outputs shown
        character(len=400) :: line
        integer :: j, kk, p
        call lst%need(8 + size(o%v, 1))
        call lst%put('')
        if (sw%design == design_oat) then
            call lst%put(' SENSITIVITIES,'//title//': percent change of the output per percent change of the '// &
                         'parameter')
        else
            call lst%put(' SENSITIVITIES,'//title//': standardised regression coefficients (R^2 of the linear '// &
                         'fit below)')
        end if
        call lst%put('')
        line = '   PARAMETER '
        do j = 1, size(which)
            line(14 + col*(j - 1):) = ' '//adjustr(output_names(which(j)))
        end do
        call lst%put(line)
        do p = 1, size(o%v, 1)
            line = '   '//sw%params(p)%name
            do j = 1, size(which)
                kk = which(j)
                if (o%valid(p, kk)) then
                    write (line(14 + col*(j - 1):), '(f13.3)') o%s(p, kk)
                else
                    line(14 + col*(j - 1):) = '          n/a'
                end if
            end do
            call lst%put(line)
        end do
        if (sw%design /= design_oat) then
            line = '   R^2'
            do j = 1, size(which)
                kk = which(j)
                if (any(o%valid(:, kk))) then
                    write (line(14 + col*(j - 1):), '(f13.3)') o%r2(kk)
                else
                    line(14 + col*(j - 1):) = '          n/a'
                end if
            end do
            call lst%put(line)
        end if
    end subroutine sensitivity_table

    !> Write the sweep result file (layout in docs/sweeps.md).
    subroutine sweep_write_h5(sw, o, fname, version, stat, errmsg)
        type(sweep_t), intent(in) :: sw                !! the sweep
        type(sweep_outcome_t), intent(in) :: o         !! design, member records, sensitivities, ranks, wall time
        character(len=*), intent(in) :: fname          !! sweep result file (.h5)
        character(len=*), intent(in) :: version        !! program version written to the file
        integer, intent(out) :: stat                   !! stat_ok, or stat_io
        character(len=msglen), intent(out) :: errmsg   !! why the file could not be written ('' when stat_ok)
        type(h5_file_t) :: h5
        character(len=:), allocatable :: deck
        character(len=32) :: labels(size(o%v, 1)), punits(size(o%v, 1))
        character(len=10) :: names(size(o%v, 1))
        character(len=len(output_units)) :: ounits(nout)
        real(wp) :: outs(nout, size(o%recs)), col(size(o%recs)), pcol(size(o%v, 1))
        integer :: icol(size(o%recs)), ipcol(size(o%v, 1))
        character(len=msglen) :: msgs(size(o%recs))
        integer :: k, np, nrun
        associate (v => o%v, recs => o%recs, s => o%s, valid => o%valid, r2 => o%r2, nranks => o%nranks, &
                   wall => o%wall)
            np = size(v, 1)
            nrun = size(v, 2)
            call h5%create(fname, stat, errmsg)
            if (stat /= 0) return
            call h5%attr_string('/', 'code', 'HHNECK '//version)
            call h5%attr_int('/', 'schema_version', sweep_schema_version)
            call h5%attr_string('/', 'title', trim(sw%title))
            call h5%attr_string('/', 'base', trim(sw%base))
            call h5%attr_string('/', 'design', trim(design_name(sw%design)))
            deck = ''
            do k = 1, size(sw%deck)
                deck = deck//sw%deck(k)%text//new_line('a')
            end do
            call h5%attr_string('/', 'sweep_deck', deck)
            deck = ''
            do k = 1, size(sw%base_lines)
                deck = deck//sw%base_lines(k)%text//new_line('a')
            end do
            call h5%attr_string('/', 'base_deck', deck)
            call h5%attr_int('/', 'ranks', nranks)
            call h5%attr_real_scalar('/', 'wall_time', wall)
            call h5%attr_int('/', 'failed_runs', count(recs%status /= 0))
            call h5%group('/params')
            do k = 1, np
                names(k) = sw%params(k)%name
                labels(k) = param_label(sw, k)
                punits(k) = param_units(sw, k)
            end do
            ounits = output_units
            where (ounits == '-') ounits = '1'   ! dimensionless, as in the result file
            call h5%write_text('/params/name', names)
            call h5%write_text('/params/what', labels)
            pcol = sw%params%low
            call h5%write_real('/params/low', pcol, [np])
            pcol = sw%params%high
            call h5%write_real('/params/high', pcol, [np])
            pcol = sw%params%nominal
            call h5%write_real('/params/nominal', pcol, [np])
            ipcol = merge(1, 0, sw%params%log_spacing)
            call h5%write_int('/params/log_spacing', ipcol, [np])
            call per_column('/params/low', punits)
            call per_column('/params/high', punits)
            call per_column('/params/nominal', punits)
            call h5%attr_string('/params/log_spacing', 'units', '1')
            call h5%group('/runs')
            call h5%write_real('/runs/inputs', v, [np, nrun])
            call per_column('/runs/inputs', punits)
            do k = 1, nrun
                outs(:, k) = recs(k)%outputs
            end do
            call h5%write_real('/runs/outputs', outs, [nout, nrun])
            call per_column('/runs/outputs', ounits)
            call h5%write_text('/runs/output_names', output_names)
            call h5%write_text('/runs/output_units', output_units)
            icol = recs%status
            call h5%write_int('/runs/status', icol, [nrun])
            msgs = recs%message
            call h5%write_text('/runs/message', msgs)
            icol = recs%rank
            call h5%write_int('/runs/rank', icol, [nrun])
            col = recs%wall
            call h5%write_real('/runs/wall', col, [nrun])
            icol = recs%nevals
            call h5%write_int('/runs/evaluations', icol, [nrun])
            col = recs%t_reached
            call h5%write_real('/runs/t_reached', col, [nrun])
            call h5%attr_string('/runs/status', 'units', '1')
            call h5%attr_string('/runs/rank', 'units', '1')
            call h5%attr_string('/runs/wall', 'units', 's')
            call h5%attr_string('/runs/evaluations', 'units', '1')
            call h5%attr_string('/runs/t_reached', 'units', 's')
            call h5%group('/sensitivity')
            if (sw%design == design_oat) then
                call h5%attr_string('/sensitivity', 'method', 'OAT elasticity')
            else
                call h5%attr_string('/sensitivity', 'method', 'standardised regression (SRC)')
            end if
            call h5%write_real('/sensitivity/coefficient', s, [np, nout])
            call h5%write_int('/sensitivity/valid', merge(1, 0, valid), [np, nout])
            call h5%write_real('/sensitivity/r2', r2, [nout])
            call h5%write_int('/sensitivity/roundoff', merge(1, 0, o%roundoff), [nout])
            call h5%attr_string('/sensitivity/coefficient', 'units', '1')
            call h5%attr_string('/sensitivity/valid', 'units', '1')
            call h5%attr_string('/sensitivity/r2', 'units', '1')
            call h5%attr_string('/sensitivity/roundoff', 'units', '1')
            call h5%attr_string('/', 'status', 'complete')
            call h5%close(.true., stat, errmsg)
        end associate
    contains
        !> Units of a dataset with one column per parameter or output: the
        !! text attribute `units` says so, the list `column_units` gives them.
        subroutine per_column(path, units)
            character(len=*), intent(in) :: path       !! the dataset
            character(len=*), intent(in) :: units(:)   !! units of each column
            call h5%attr_string(path, 'units', 'per column in column_units')
            call h5%attr_strings(path, 'column_units', units)
        end subroutine per_column
    end subroutine sweep_write_h5

end module hn_sweep_report
