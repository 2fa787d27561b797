!> hhneck: run one case deck, given by name or on standard input.
!!
!!   hhneck input/case6-2.inp              (or: hhneck < input/case6-2.inp)
!!   hhneck --h5 out.h5 input/nbdl15g.inp
!!   hhneck --set 'BODY.HEAD.MASS*=1.1' input/nbdl15g.inp
!!   hhneck --sweep --h5 sweep.h5 input/sweep_nbdl_oat.inp
!!
!! The listing goes to standard output, diagnostics to standard error.
!! `hhneck --help` lists the options; exit codes are in docs/errors.md.
program hhneck
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
    use hn_kinds, only: msglen, wp, i8
    use hn_case, only: case_t, path_len
    use hn_deck, only: read_case
    use hn_deck_reader, only: parse_real, stdin_path, add_environment_path, int_str
    use hn_version, only: code_version
    use hn_run, only: run_state_t, run_result_t, exit_usage, exit_deck, exit_ok, exit_output, &
                      exit_members_failed, exit_interrupted
    use hn_sweep, only: sweep_t, member_record_t, read_sweep, sweep_design, run_member
    use hn_sweep_report, only: sweep_finish
    use hn_calibrate, only: calibration_t, read_calibration, calibrate
    use hn_signals, only: catch_signals, defer_signals
    use hn_progress, only: progress_off, progress_auto, progress_on, run_budget
    use hn_posix, only: is_terminal, stdin_kind, kind_char_device, exit_now
    use hn_set_option, only: set_card
    use hn_results, only: results_replaceable
    use hn_statics, only: statics_execute
    implicit none
    type(case_t) :: cs
    type(run_result_t) :: res
    type(run_state_t) :: run
    character(len=path_len) :: h5name, arg, deck, source
    character(len=path_len), allocatable :: search(:)
    character(len=path_len), allocatable :: change_cards(:)   ! --change and --set card images, in order
    integer, allocatable :: set_of(:)   ! for each of change_cards: the number of its --set option (0: --change)
    character(len=msglen) :: msg, budget_warning
    character(len=80) :: card
    logical :: h5_given, no_h5, check_only, sweep, calib, overwrite, ok
    integer :: i, stat, nargs, progress, max_steps, n
    real(wp) :: sample, rtol, max_wall

    ! until the deck is read there is nothing to close: a signal ends the program at once
    call catch_signals(exit_interrupted)
    h5_given = .false.; no_h5 = .false.; check_only = .false.; sweep = .false.; calib = .false.
    overwrite = .false.
    sample = -1.0_wp
    rtol = -1.0_wp
    max_wall = -1.0_wp
    max_steps = -1
    progress = progress_auto
    h5name = ''
    deck = ''
    allocate (search(0), change_cards(0), set_of(0))
    nargs = command_argument_count()
    i = 1
    do while (i <= nargs)
        call get_command_argument(i, arg)
        select case (arg)
        case ('--h5')
            call h5name_argument()
        case ('--no-h5')
            no_h5 = .true.
        case ('--rtol')
            rtol = real_argument('--rtol needs a tolerance in [1E-14, 0.1]', 1.0e-14_wp, 0.1_wp)
        case ('--sample')
            sample = real_argument('--sample needs a positive interval in seconds below 1E4', 1.0e-9_wp, 1.0e4_wp)
        case ('--max-wall')
            max_wall = real_argument('--max-wall needs a wall time in seconds in [1E-3, 1E7]', 1.0e-3_wp, 1.0e7_wp)
        case ('--max-steps')
            max_steps = nint(real_argument('--max-steps needs a whole number of steps in [1, 2E9]', 1.0_wp, 2.0e9_wp))
        case ('--progress')
            progress = progress_on
        case ('--no-progress')
            progress = progress_off
        case ('-I', '--include-path')
            if (i == nargs) call usage(trim(arg)//' needs a directory')
            i = i + 1
            call get_command_argument(i, arg)
            search = [character(len=path_len) :: search, arg]
        case ('--change')
            if (i == nargs) call usage('--change needs a CHANGE card image, e.g. --change ''CHANGE    HEADM     '// &
                                       'BODY      HEAD      MASS      SCALE     1.1''')
            i = i + 1
            call get_command_argument(i, arg, length=n)
            if (n > len(arg)) call usage('--change: found a card image of more than 80 columns')
            change_cards = [character(len=path_len) :: change_cards, arg]
            set_of = [set_of, 0]
        case ('--set')
            if (i == nargs) call usage('--set needs KEY=VALUE or KEY*=FACTOR, e.g. --set BODY.HEAD.MASS*=1.1')
            i = i + 1
            call get_command_argument(i, arg, length=n)
            if (n > len(arg)) call usage('--set: found an argument of more than '//trim(int_str(len(arg)))// &
                                         ' characters')
            call set_card(trim(arg), count(set_of > 0) + 1, card, stat, msg)
            if (stat /= 0) call usage(trim(msg))
            change_cards = [character(len=path_len) :: change_cards, card]
            set_of = [set_of, count(set_of > 0) + 1]
        case ('--overwrite')
            overwrite = .true.
        case ('--check')
            check_only = .true.
        case ('--sweep')
            sweep = .true.
        case ('--calibrate')
            calib = .true.
        case ('--version')
            write (output_unit, '(a)') 'hhneck '//code_version
            stop 0, quiet=.true.
        case ('--help', '-h')
            call help()
        case default
            if (arg(1:1) == '-' .and. len_trim(arg) > 1) call usage('unknown option "'//trim(arg)//'"')
            if (len_trim(deck) > 0) call usage('only one deck may be given; found "'//trim(deck)//'" and "'// &
                                               trim(arg)//'"')
            deck = arg
        end select
        i = i + 1
    end do
    call add_environment_path(search)   ! HHNECK_PATH after the -I directories
    if (len_trim(deck) == 0 .or. deck == '-') then
        if (is_terminal(0) .and. stdin_kind() == kind_char_device) &
            call usage('no deck: give a deck file (hhneck DECK) or redirect standard input (hhneck < DECK)')
        deck = stdin_path
        source = 'stdin'
    else
        source = deck
    end if

    if ((sweep .or. calib) .and. size(change_cards) > 0) &
        call usage('--change and --set change the deck of a single run; a sweep or calibration varies its '// &
                   'parameters through its own PARAM cards')
    if (sweep) call run_sweep()
    if (calib) call run_calibration()
    call read_case(trim(deck), trim(source), cs, stat, msg, search, change_cards)
    call name_set_options(msg)
    call stop_on_deck_error('')
    cs%deck_file = 'stdin'
    if (source /= 'stdin') cs%deck_file = base_name(deck)
    do i = 1, size(cs%warnings)
        write (error_unit, '(a)') 'hhneck: warning: '//trim(cs%warnings(i))
    end do
    if (max_wall > 0.0_wp) cs%wall_limit = max_wall
    if (max_steps > 0) cs%step_limit = max_steps
    ! a fixed-step run beyond its step limit is refused, a very long one named, before it starts
    call run_budget(cs, stat, msg, budget_warning)
    call stop_on_deck_error('')
    if (len_trim(budget_warning) > 0) write (error_unit, '(a)') 'hhneck: warning: '//trim(budget_warning)
    if (check_only) then
        write (error_unit, '(a)') 'hhneck: deck is valid: '//trim(cs%model%title)
        stop 0, quiet=.true.
    end if
    if (sample > 0.0_wp) then
        if ((cs%t_end - cs%t_start)/sample > 1.0e7_wp) call usage('--sample gives more than 1E7 samples for this run')
        cs%sample_dt = sample
    end if
    if (rtol > 0.0_wp) then
        cs%rtol = rtol
        cs%atol = rtol*1.0e-3_wp
    end if
    cs%progress = progress
    if (.not. h5_given) then
        h5name = cs%h5file
        ! a variant deck that inherits an INCLUDEd deck's H5FILE: the file named after the variant
        if (cs%h5file_included .and. source /= 'stdin') h5name = stem(base_name(deck))//'.h5'
    end if
    if (no_h5) h5name = ''
    ! a result file of another deck is replaced only on request: refused before the run starts
    if (len_trim(h5name) > 0 .and. .not. overwrite) then
        call results_replaceable(trim(h5name), cs, ok, msg)
        if (.not. ok) then
            write (error_unit, '(a)') 'hhneck: '//trim(msg)
            stop exit_output, quiet=.true.
        end if
    end if
    ! from here on a signal stops the run at its next step, files closed and marked
    call defer_signals()
    if (allocated(cs%statics_times)) then
        call statics_execute(cs, output_unit, trim(h5name), res)   ! STATICS: equilibria, no integration
    else
        call run%execute(cs, output_unit, trim(h5name), res)
    end if
    if (res%exit_code /= exit_ok) then
        write (error_unit, '(a)') 'hhneck: '//trim(res%message)
        if (len_trim(res%file_note) > 0) write (error_unit, '(a)') 'hhneck: '//trim(res%file_note)
        ! skip the HDF5 library's exit handler: after a write failure (a full
        ! disk) it would try again to flush a file that is already given up
        flush (output_unit)
        flush (error_unit)
        call exit_now(res%exit_code)
    end if
    if (len_trim(res%file_note) > 0) write (error_unit, '(a)') 'hhneck: '//trim(res%file_note)
    if (len_trim(res%warning) > 0) write (error_unit, '(a)') 'hhneck: '//trim(res%warning)
    write (error_unit, '(a,f8.3,a,i0,a)') 'hhneck: done in ', res%wall, ' s wall time, ', res%nevals, &
        ' dynamics evaluations'

contains

    !> A parameter sweep read from the deck, its members run one after the
    !! other (the MPI driver is `fpm run --example sweep_mpi`).
    subroutine run_sweep()
        type(sweep_t) :: sw
        type(member_record_t), allocatable :: recs(:)
        real(wp), allocatable :: v(:, :)
        integer(i8) :: c0, c1, rate
        integer :: r
        call read_sweep(trim(deck), trim(source), sw, stat, msg, search)
        call stop_on_deck_error('sweep ')
        if (check_only) then
            write (error_unit, '(a)') 'hhneck: sweep deck is valid: '//trim(sw%title)
            stop 0, quiet=.true.
        end if
        if (.not. h5_given) h5name = sw%h5file
        if (no_h5) h5name = ''
        call defer_signals()
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
        stop 0, quiet=.true.
    end subroutine run_sweep

    !> A calibration deck (docs/sweeps.md, docs/validation.md): the fit
    !! history and the fitted parameters on standard output.
    subroutine run_calibration()
        type(calibration_t) :: cal
        real(wp), allocatable :: v(:)
        real(wp) :: j
        integer :: n
        call read_calibration(trim(deck), trim(source), cal, stat, msg, search)
        call stop_on_deck_error('calibration ')
        if (check_only) then
            write (error_unit, '(a)') 'hhneck: calibration deck is valid: '//trim(cal%title)
            stop 0, quiet=.true.
        end if
        allocate (v(size(cal%par)))
        call calibrate(cal, output_unit, v, j, n)
        write (error_unit, '(a,i0,a,f8.5)') 'hhneck: calibration finished after ', n, ' evaluations; objective ', j
        stop 0, quiet=.true.
    end subroutine run_calibration

    !> After reading a deck: on an error, its located message on stderr
    !! ('hhneck: <kind>deck error: ...') and exit code exit_deck.
    subroutine stop_on_deck_error(kind)
        character(len=*), intent(in) :: kind   !! '' or the deck kind with a trailing blank ('sweep ')
        if (stat == 0) return
        write (error_unit, '(a)') 'hhneck: '//kind//'deck error: '//trim(msg)
        stop exit_deck, quiet=.true.
    end subroutine stop_on_deck_error

    subroutine h5name_argument()
        if (i == nargs) call usage('--h5 needs a file name')
        i = i + 1
        call get_command_argument(i, h5name)
        if (len_trim(h5name) == 0) call usage('--h5 needs a file name')
        h5_given = .true.
    end subroutine h5name_argument

    !> The next argument as a real number in [lo, hi] (checked before conversion).
    real(wp) function real_argument(problem, lo, hi) result(v)
        character(len=*), intent(in) :: problem
        real(wp), intent(in) :: lo, hi
        logical :: ok
        if (i == nargs) call usage(problem)
        i = i + 1
        call get_command_argument(i, arg)
        ok = len_trim(arg) <= 40
        if (ok) call parse_real(trim(arg), v, ok)
        if (.not. ok) call usage(problem//', found "'//trim(arg)//'"')
        if (.not. (v >= lo .and. v <= hi)) call usage(problem//', found "'//trim(arg)//'"')
    end function real_argument

    !> The change notes and a deck error of a --set option's CHANGE card
    !! located as "--set N" (read_case locates every option card as
    !! "--change K", K counting --change and --set together).
    subroutine name_set_options(errmsg)
        character(len=*), intent(inout) :: errmsg   !! the deck error, if any
        integer :: k, j
        if (allocated(cs%deck)) then
            do j = 1, size(cs%deck)
                if (cs%deck(j)%source /= '--change') cycle
                if (cs%deck(j)%line < 1 .or. cs%deck(j)%line > size(set_of)) cycle
                if (set_of(cs%deck(j)%line) == 0) cycle
                cs%deck(j)%source = '--set'
                cs%deck(j)%line = set_of(cs%deck(j)%line)
            end do
        end if
        do k = size(set_of), 1, -1     ! "--change 12" before "--change 1"
            if (set_of(k) == 0) cycle
            call relabel(errmsg, k)
            if (index(errmsg, '--set '//trim(int_str(set_of(k)))//',') > 0 .or. &
                index(errmsg, '--set '//trim(int_str(set_of(k)))//' ') > 0) &
                errmsg = trim(errmsg)//' (--set '//trim(int_str(set_of(k)))//' stands for the card '''// &
                         trim(change_cards(k))//''')'
            ! an ambiguous FIELDn change: the key that names field F2 of the card too
            if (index(errmsg, 'in F7:') > 0 .and. index(errmsg, '--set '//trim(int_str(set_of(k)))) > 0) &
                errmsg = trim(errmsg)//'; as --set: '//trim(adjustl(change_cards(k)(31:40)))//'.'// &
                         trim(adjustl(change_cards(k)(41:50)))//'.<its F2>.F'//trim(change_cards(k)(26:30))
            if (allocated(cs%changes)) then
                do j = 1, size(cs%changes)
                    call relabel(cs%changes(j), k)
                end do
            end if
        end do
    end subroutine name_set_options

    subroutine relabel(text, k)
        character(len=*), intent(inout) :: text
        integer, intent(in) :: k
        character(len=:), allocatable :: old, new
        integer :: p
        old = '--change '//trim(int_str(k))
        new = '--set '//trim(int_str(set_of(k)))
        do
            p = index(text, old)
            if (p == 0) exit
            if (p + len(old) <= len(text)) then
                if (index('0123456789', text(p + len(old):p + len(old))) > 0) exit
            end if
            text = text(1:p - 1)//new//text(p + len(old):)
        end do
    end subroutine relabel

    !> A path without its directories.
    function base_name(path) result(s)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: s
        s = trim(path(index(trim(path), '/', back=.true.) + 1:))
    end function base_name

    !> A file name without its last extension ("x.inp" -> "x").
    function stem(name) result(s)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: s
        integer :: p
        p = index(name, '.', back=.true.)
        s = name
        if (p > 1) s = name(1:p - 1)
    end function stem

    subroutine usage(problem)
        character(len=*), intent(in) :: problem
        write (error_unit, '(a)') 'hhneck: '//problem
        write (error_unit, '(a)') 'usage: hhneck [OPTIONS] [DECK]     (or: hhneck [OPTIONS] < DECK; '// &
            'hhneck --help for the options)'
        stop exit_usage, quiet=.true.
    end subroutine usage

    subroutine help()
        write (output_unit, '(a)') &
            'usage: hhneck [OPTIONS] [DECK]', &
            '       hhneck [OPTIONS] < DECK', &
            '', &
            'Runs the case deck DECK (a file, or standard input when DECK is absent or -): the', &
            '54-DOF head/neck model of Huston, Huston & Harlow (1978). The listing goes to standard', &
            'output, messages to standard error, results to the HDF5 file the deck names (H5FILE;', &
            'a variant deck that INCLUDEs the H5FILE of another writes DECK''s name .h5 instead).', &
            'Deck format: docs/deck-format.md; result file: docs/output-format.md.', &
            '', &
            'options:', &
            '  --h5 FILE          write the HDF5 results to FILE (instead of the H5FILE card);', &
            '                     a missing directory is created, an older FILE of the same deck', &
            '                     is replaced', &
            '  --overwrite        replace a result file written by another deck (without it the', &
            '                     run is refused before it starts, exit 4, the file kept)', &
            '  --no-h5            write no HDF5 file', &
            '  --sample SECONDS   HDF5 sampling interval (instead of the OUTPUT card)', &
            '  --rtol TOL         relative tolerance of the error-controlled integrators', &
            '                     (instead of CONTROL F5; the absolute tolerance becomes TOL/1000)', &
            '  --change ''CARD''    add the CHANGE card CARD (an 80-column card image as in a deck,', &
            '                     e.g. ''CHANGE    E12       FAMILY    DISCS     E         SCALE     1.2'')', &
            '                     after the deck''s own cards (repeatable; docs/deck-format.md);', &
            '                     the listing and the result file note it as "--change N"', &
            '  --set KEY=VALUE    a change without a card image (repeatable): KEY*=FACTOR scales;', &
            '                     BODY.body.MASS=4.2, BODY.body.INERTIA*=1.1,', &
            '                     FAMILY.family.item*=1.2 (e.g. FAMILY.DISCS.E*=1.2),', &
            '                     CARD.Fn=V, CARD.name.Fn=V, CARD.name.F2text.Fn=V (field n of the', &
            '                     card, e.g. CONTROL.F5=1E-7, LIMIT.C7.RY.F5*=2); noted "--set N"', &
            '  --check            read and check the deck (warnings included), do not run', &
            '  --sweep            the deck is a parameter-sweep deck (docs/sweeps.md)', &
            '  --calibrate        the deck is a calibration deck: fit its parameters (docs/sweeps.md)', &
            '  -I DIR, --include-path DIR', &
            '                     look for INCLUDE files (and a sweep''s BASE deck) in DIR too', &
            '                     (repeatable); after the including file''s directory and the', &
            '                     working directory, and', &
            '                     before the directories of the environment variable HHNECK_PATH', &
            '                     (colon separated), e.g. the project directory of the shipped decks', &
            '  --progress         show progress on standard error (simulated and wall time, step,', &
            '                     time to go); by default shown only on a terminal, for long runs', &
            '  --no-progress      never show progress', &
            '  --max-wall SECONDS stop the run after this wall time (exit 3, files kept, marked', &
            '                     incomplete, with the likely cause); also the RUNLIMIT card', &
            '  --max-steps N      stop the run after N integration steps (exit 3, likewise)', &
            '  --version          print the version', &
            '  -h, --help         print this help', &
            '', &
            'exit codes (docs/errors.md):', &
            '  0  run complete           3  run stopped early (divergence, a run limit); files kept', &
            '  1  bad command line       4  the result file could not be written', &
            '  2  deck error (located)   5  interrupted by SIGINT or SIGTERM; files kept', &
            '                            6  a sweep finished but some member runs failed'
        stop 0, quiet=.true.
    end subroutine help

end program hhneck
