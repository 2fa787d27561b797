!> hhneck: run one case deck read from standard input.
!!
!!   fpm run < input/case6-2.inp
!!   fpm run -- --h5 out.h5 < input/nbdl15g.inp
!!
!!   fpm run -- --sweep --h5 sweep.h5 < input/sweep_nbdl_oat.inp
!!
!! The listing goes to standard output, diagnostics to standard error.
!! Exit codes are listed in docs/errors.md.
program hhneck
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
    use hn_kinds, only: msglen, wp, i8
    use hn_case, only: case_t, path_len
    use hn_deck, only: read_case
    use hn_version, only: code_version
    use hn_run, only: run_state_t, run_result_t, exit_usage, exit_deck, exit_ok, exit_output, &
                      exit_members_failed
    use hn_sweep, only: sweep_t, member_record_t, read_sweep, sweep_design, run_member
    use hn_sweep_report, only: sweep_finish
    use hn_signals, only: catch_signals
    implicit none
    type(case_t) :: cs
    type(run_result_t) :: res
    type(run_state_t) :: run
    character(len=path_len) :: h5name, arg
    character(len=msglen) :: msg
    logical :: h5_given, no_h5, check_only, sweep
    integer :: i, stat, nargs
    real(wp) :: sample, rtol

    h5_given = .false.; no_h5 = .false.; check_only = .false.; sweep = .false.
    sample = -1.0_wp
    rtol = -1.0_wp
    h5name = ''
    nargs = command_argument_count()
    i = 1
    do while (i <= nargs)
        call get_command_argument(i, arg)
        select case (arg)
        case ('--h5')
            if (i == nargs) call usage('--h5 needs a file name')
            i = i + 1
            call get_command_argument(i, h5name)
            h5_given = .true.
        case ('--no-h5')
            no_h5 = .true.
        case ('--rtol')
            if (i == nargs) call usage('--rtol needs a tolerance')
            i = i + 1
            call get_command_argument(i, arg)
            read (arg, *, iostat=stat) rtol
            if (stat /= 0 .or. .not. (rtol >= 1.0e-14_wp .and. rtol <= 0.1_wp)) &
                call usage('--rtol needs a tolerance in [1E-14, 0.1], found "'//trim(arg)//'"')
        case ('--sample')
            if (i == nargs) call usage('--sample needs an interval in seconds')
            i = i + 1
            call get_command_argument(i, arg)
            read (arg, *, iostat=stat) sample
            if (stat /= 0 .or. .not. (sample > 0.0_wp .and. sample < 1.0e4_wp)) &
                call usage('--sample needs a positive interval in seconds, found "'//trim(arg)//'"')
        case ('--check')
            check_only = .true.
        case ('--sweep')
            sweep = .true.
        case ('--version')
            write (output_unit, '(a)') 'hhneck '//code_version
            stop
        case ('--help', '-h')
            call usage('')
        case default
            call usage('unknown option "'//trim(arg)//'"')
        end select
        i = i + 1
    end do

    if (sweep) call run_sweep()
    call read_case('/dev/stdin', 'stdin', cs, stat, msg)
    if (stat /= 0) then
        write (error_unit, '(a)') 'hhneck: deck error: '//trim(msg)
        stop exit_deck, quiet=.true.
    end if
    do i = 1, size(cs%warnings)
        write (error_unit, '(a)') 'hhneck: warning: '//trim(cs%warnings(i))
    end do
    if (check_only) then
        write (error_unit, '(a)') 'hhneck: deck is valid: '//trim(cs%model%title)
        stop
    end if
    if (sample > 0.0_wp) then
        if ((cs%t_end - cs%t_start)/sample > 1.0e7_wp) call usage('--sample gives more than 1E7 samples for this run')
        cs%sample_dt = sample
    end if
    if (rtol > 0.0_wp) then
        cs%rtol = rtol
        cs%atol = rtol*1.0e-3_wp
    end if
    if (.not. h5_given) h5name = cs%h5file
    if (no_h5) h5name = ''
    call catch_signals()
    call run%execute(cs, output_unit, trim(h5name), res)
    if (res%exit_code /= exit_ok) then
        write (error_unit, '(a)') 'hhneck: '//trim(res%message)
        if (len_trim(h5name) > 0) write (error_unit, '(a)') 'hhneck: results up to t = '// &
            trim(real_text(res%t_reached))//' s kept in '//trim(h5name)//' (marked incomplete)'
        stop res%exit_code, quiet=.true.
    end if
    if (len_trim(res%warning) > 0) write (error_unit, '(a)') 'hhneck: '//trim(res%warning)
    write (error_unit, '(a,f8.3,a,i0,a)') 'hhneck: done in ', res%wall, ' s wall time, ', res%nevals, &
        ' dynamics evaluations'

contains

    !> A parameter sweep read from standard input, its members run one
    !! after the other (the MPI driver is `fpm run --example sweep_mpi`).
    subroutine run_sweep()
        type(sweep_t) :: sw
        type(member_record_t), allocatable :: recs(:)
        real(wp), allocatable :: v(:, :)
        integer(i8) :: c0, c1, rate
        integer :: r
        call read_sweep('/dev/stdin', 'stdin', sw, stat, msg)
        if (stat /= 0) then
            write (error_unit, '(a)') 'hhneck: sweep deck error: '//trim(msg)
            stop exit_deck, quiet=.true.
        end if
        if (check_only) then
            write (error_unit, '(a)') 'hhneck: sweep deck is valid: '//trim(sw%title)
            stop
        end if
        if (.not. h5_given) h5name = sw%h5file
        if (no_h5) h5name = ''
        v = sweep_design(sw)
        allocate (recs(size(v, 2)))
        call system_clock(c0, rate)
        do r = 1, size(v, 2)
            call run_member(sw, v(:, r), recs(r))
            write (error_unit, '(a,i0,a,i0,a,i0,a,f7.2,a)') 'hhneck: sweep run ', r, ' of ', size(v, 2), &
                ': exit ', recs(r)%status, ', ', recs(r)%wall, ' s'
        end do
        call system_clock(c1)
        call sweep_finish(sw, v, recs, 1, real(c1 - c0, wp)/real(rate, wp), output_unit, trim(h5name), &
                          code_version, stat, msg)
        if (stat /= 0) then
            write (error_unit, '(a)') 'hhneck: '//trim(msg)
            stop exit_output, quiet=.true.
        end if
        if (any(recs%status /= 0)) then
            write (error_unit, '(a,i0,a,i0,a)') 'hhneck: sweep finished; ', count(recs%status /= 0), ' of ', &
                size(recs), ' member runs failed (listed in the listing and the result file)'
            stop exit_members_failed, quiet=.true.
        end if
        write (error_unit, '(a,i0,a)') 'hhneck: sweep finished; all ', size(recs), ' member runs complete'
        stop
    end subroutine run_sweep

    subroutine usage(problem)
        character(len=*), intent(in) :: problem
        if (len(problem) > 0) write (error_unit, '(a)') 'hhneck: '//problem
        write (error_unit, '(a)') 'usage: hhneck [--sweep] [--h5 FILE | --no-h5] [--sample SECONDS] [--rtol TOL] '// &
            '[--check] [--version] < DECK'
        if (len(problem) > 0) stop exit_usage, quiet=.true.
        stop
    end subroutine usage

    function real_text(v) result(s)
        real(wp), intent(in) :: v
        character(len=24) :: s
        write (s, '(f12.5)') v
        s = adjustl(s)
    end function real_text

end program hhneck
