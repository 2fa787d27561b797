!> Running a case: initial state, posture holding, the integrator, the
!! output schedule (samples, print times, dump times), divergence checks,
!! the HDF5 result file and the listing.
module hn_run
    use hn_kinds, only: wp, zero, msglen, i8
    use hn_case, only: case_t
    use hn_dynamics, only: model_ode_t, model_ode_init, coordinates_to_state
    use hn_integrators, only: integrator_t, rk4_t, dopri5_t
    use hn_channels, only: channel_set_t, channels_define, channels_compute
    use hn_results, only: results_t
    use hn_listing, only: listing_t
    use hn_dump, only: dump_record
    implicit none
    private

    public :: run_case, run_result_t, make_integrator, code_version

    character(len=*), parameter :: code_version = '0.1.0'

    integer, parameter, public :: exit_ok = 0, exit_usage = 1, exit_deck = 2, exit_diverged = 3, &
                                  exit_output = 4

    !> What happened in a run.
    type :: run_result_t
        integer :: exit_code = exit_ok
        character(len=12) :: status = 'complete'
        character(len=msglen) :: message = ''
        real(wp) :: t_reached = zero
        integer :: nevals = 0
        integer :: nsteps = 0
        real(wp) :: wall = zero          !! wall-clock time of the integration [s]
        real(wp), allocatable :: times(:), rows(:, :)   !! the listing rows
        integer :: nrows = 0
    end type run_result_t

contains

    !> The integrator named on the CONTROL card, with the case's step and tolerances.
    subroutine make_integrator(cs, integ)
        type(case_t), intent(in) :: cs
        class(integrator_t), allocatable, intent(out) :: integ
        select case (cs%integrator)
        case ('DOPRI5'); allocate (dopri5_t :: integ)
        case default; allocate (rk4_t :: integ)
        end select
        integ%h = cs%h
        integ%rtol = cs%rtol
        integ%atol = cs%atol
    end subroutine make_integrator

    !> Run the case, writing the listing on unit `lu` and results to
    !! `h5name` ('' for none).
    subroutine run_case(cs, lu, h5name, res)
        type(case_t), intent(inout) :: cs
        integer, intent(in) :: lu
        character(len=*), intent(in) :: h5name
        type(run_result_t), intent(out) :: res
        type(model_ode_t) :: sys
        class(integrator_t), allocatable :: integ
        type(channel_set_t) :: ch
        type(results_t) :: out
        type(listing_t) :: lst
        real(wp), allocatable :: y(:), dydt(:), vmax(:), vmin(:), tmax(:), tmin(:)
        real(wp) :: t, tnext, tsample, tprint, tol
        integer :: stat, nf, ks, kp, kd, nprint_max
        integer(i8) :: c0, c1, rate
        character(len=msglen) :: msg
        logical :: do_sample, do_print, do_dump

        call lst%start(lu, cs%model%title, code_version)
        call lst%echo_deck(cs)
        call channels_define(cs, ch)
        call model_ode_init(sys, cs%model)
        nf = sys%ws%nfree
        allocate (y(2*nf), dydt(2*nf))
        call coordinates_to_state(sys%ws, cs%x0, cs%xd0, y)
        t = cs%t_start

        if (cs%hold_posture) then
            call sys%rhs(t, y, dydt, stat, msg)
            if (stat /= 0) then
                call fail(exit_diverged, 'posture holding: '//trim(msg)); return
            end if
            sys%model%q_hold(sys%ws%ifree) = -matmul(sys%ws%a(sys%ws%ifree, sys%ws%ifree), dydt(nf + 1:))
            cs%model%q_hold = sys%model%q_hold
        end if
        call lst%model_summary(cs)

        call make_integrator(cs, integ)
        call sys%rhs(t, y, dydt, stat, msg)
        if (stat /= 0) then
            call fail(exit_diverged, trim(msg)); return
        end if
        ch%head_r0 = sys%ws%kin%r(:, cs%head) - sys%ws%kin%r(:, cs%t1)
        ch%t1_r0 = sys%ws%kin%r(:, cs%t1)
        if (len_trim(h5name) > 0) then
            call out%open(cs, ch, trim(h5name), code_version, stat, msg)
            if (stat /= 0) then
                call fail(exit_output, trim(msg)); return
            end if
        end if
        nprint_max = nint((cs%t_end - cs%t_start)/cs%print_dt) + 2
        allocate (res%times(nprint_max), res%rows(ch%n, nprint_max))
        allocate (vmax(ch%n), vmin(ch%n), tmax(ch%n), tmin(ch%n))
        vmax = -huge(1.0_wp); vmin = huge(1.0_wp); tmax = t; tmin = t

        tol = 1.0e-9_wp*max(cs%sample_dt, 1.0e-6_wp)
        ks = 0; kp = 0; kd = 1
        call system_clock(c0, rate)
        do
            tsample = cs%t_start + ks*cs%sample_dt
            tprint = cs%t_start + kp*cs%print_dt
            do_sample = abs(t - tsample) <= tol
            do_print = abs(t - tprint) <= tol
            do_dump = .false.
            if (kd <= size(cs%dump_times)) do_dump = abs(t - cs%dump_times(kd)) <= tol
            call channels_compute(cs, sys%ws, t, ch)
            call track_peaks()
            if (do_sample) then
                call out%sample(t, ch, sys%ws)
                ks = ks + 1
            end if
            if (do_print) then
                res%nrows = res%nrows + 1
                res%times(res%nrows) = t
                res%rows(:, res%nrows) = ch%value
                kp = kp + 1
                call out%flush(ch)
            end if
            if (do_dump) then
                if (out%active) call dump_record(out%h5, cs%model, sys%ws, t, stat, msg)
                kd = kd + 1
            end if
            res%t_reached = t
            if (t >= cs%t_end - tol) exit
            tnext = min(cs%t_start + ks*cs%sample_dt, cs%t_start + kp*cs%print_dt, cs%t_end)
            if (kd <= size(cs%dump_times)) tnext = min(tnext, cs%dump_times(kd))
            call integ%advance(sys, t, y, tnext, stat, msg)
            if (stat == 0 .and. .not. all(abs(y) <= huge(1.0_wp))) then
                stat = 1
                write (msg, '(a,es12.5,a)') 'the state became NaN or infinite by t = ', tnext, ' s'
            end if
            if (stat /= 0) then
                call fail(exit_diverged, 'run stopped: '//trim(msg)); exit
            end if
            t = tnext
            call sys%rhs(t, y, dydt, stat, msg)
            if (stat /= 0) then
                call fail(exit_diverged, 'run stopped: '//trim(msg)); exit
            end if
        end do
        call system_clock(c1)
        res%wall = real(c1 - c0, wp)/real(rate, wp)
        res%nevals = sys%nevals
        res%nsteps = integ%nsteps

        call lst%histories(ch, res%times, res%rows, res%nrows)
        call lst%peaks(ch, vmax, tmax, vmin, tmin)
        write (msg, '(a,f9.4,a,i0,a,i0,a,f8.3,a)') 'END OF RUN AT T = ', res%t_reached, ' S: ', res%nsteps, &
            ' STEPS, ', res%nevals, ' DYNAMICS EVALUATIONS, ', res%wall, ' S WALL TIME'
        call lst%message(msg)
        if (res%exit_code /= exit_ok) call lst%message('RUN INCOMPLETE: '//trim(res%message))
        call out%close(ch, trim(res%status), trim(res%message), stat, msg)
        if (stat /= 0 .and. res%exit_code == exit_ok) call fail(exit_output, trim(msg))
    contains
        subroutine fail(code, text)
            integer, intent(in) :: code
            character(len=*), intent(in) :: text
            res%exit_code = code
            res%status = 'incomplete'
            res%message = text
        end subroutine fail
        subroutine track_peaks()
            integer :: k
            do k = 1, ch%n
                if (ch%value(k) > vmax(k)) then
                    vmax(k) = ch%value(k); tmax(k) = t
                end if
                if (ch%value(k) < vmin(k)) then
                    vmin(k) = ch%value(k); tmin(k) = t
                end if
            end do
        end subroutine track_peaks
    end subroutine run_case

end module hn_run
