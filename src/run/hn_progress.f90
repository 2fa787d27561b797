!> Progress of a long run on standard error, and the limits that stop a run
!! that cannot finish in reasonable time.
!!
!! Progress (simulated time, wall time, step size, estimated time to
!! finish) is shown when asked, or when standard error is a terminal and the
!! run has taken more than a few seconds: on a terminal one line rewritten in
!! place, otherwise a line every few seconds. A wall-time or step-count
!! limit (RUNLIMIT card, --max-wall, --max-steps) makes `update` return a
!! non-zero stat with a message; limit_diagnosis then says whether the step
!! is held down by stiffness, and what to do.
!!
!! The run loop needs three lines: start before it, update after every
!! step, finish after it.
module hn_progress
    use, intrinsic :: iso_fortran_env, only: error_unit
    use hn_kinds, only: wp, zero, msglen, i8
    use hn_status, only: stat_ok, stat_step_failed, stat_bad_input
    use hn_posix, only: is_terminal
    use hn_dynamics, only: model_ode_t, dyn_workspace_t, dynamics_setup, dynamics_evaluate
    use hn_case, only: case_t
    use hn_sorting, only: sort_index
    use hn_integrators, only: spectral_radius
    use hn_tree, only: dof_label
    use hn_linsolve, only: solver_gauss
    implicit none
    private

    public :: progress_t, limit_diagnosis, fixed_steps, run_budget, remedy, stop_remedy

    !> What holds a run's step down (`remedy`).
    integer, parameter, public :: held_by_stiffness = 1   !! h |lambda| of order one: stability
    integer, parameter, public :: held_by_accuracy = 2    !! h |lambda| small: the tolerance or a fixed step

    integer, parameter, public :: progress_off = 0, progress_auto = 1, progress_on = 2

    real(wp), parameter :: first_after = 2.0_wp     !! automatic progress only for runs longer than this [s wall]
    real(wp), parameter :: tty_every = 0.5_wp       !! terminal refresh [s wall]
    real(wp), parameter :: log_every = 5.0_wp       !! one line this often when not a terminal [s wall]
    real(wp), parameter :: many_steps = 1.0e6_wp    !! a fixed-step run of more steps is named before it starts

    !> Progress display and run limits of one run.
    type :: progress_t
        integer :: mode = progress_off
        logical :: tty = .false.
        real(wp) :: wall_limit = zero    !! [s], 0 = none
        integer :: step_limit = 0        !! 0 = none
        real(wp) :: t0 = zero, t_end = zero
        integer(i8) :: c0 = 0, rate = 1, shown = 0
        logical :: printed = .false.
    contains
        procedure :: start => progress_start
        procedure :: update => progress_update
        procedure :: finish => progress_finish
    end type progress_t

contains

    !> Start the clock. mode: progress_off, progress_auto (shown on a
    !! terminal once the run takes a while) or progress_on (always).
    subroutine progress_start(me, t0, t_end, mode, wall_limit, step_limit)
        class(progress_t), intent(inout) :: me
        real(wp), intent(in) :: t0                !! simulated start time [s]
        real(wp), intent(in) :: t_end             !! simulated end time [s]
        integer, intent(in) :: mode               !! progress_off, progress_auto or progress_on
        real(wp), intent(in) :: wall_limit        !! stop after this wall time [s] (0: none)
        integer, intent(in) :: step_limit         !! stop after this many steps (0: none)
        me%mode = mode
        me%tty = is_terminal(2)
        if (mode == progress_auto .and. .not. me%tty) me%mode = progress_off
        me%t0 = t0
        me%t_end = t_end
        me%wall_limit = wall_limit
        me%step_limit = step_limit
        me%printed = .false.
        call system_clock(me%c0, me%rate)
        me%shown = me%c0
    end subroutine progress_start

    !> After a step: show progress when due; stat /= 0 with a message when
    !! a limit is reached (the run should stop, exit 3).
    subroutine progress_update(me, t, h, nsteps, stat, errmsg)
        class(progress_t), intent(inout) :: me
        real(wp), intent(in) :: t            !! simulated time reached [s]
        real(wp), intent(in) :: h            !! size of the last step [s]
        integer, intent(in) :: nsteps        !! steps taken so far
        integer, intent(out) :: stat         !! stat_ok, or stat_step_failed when a limit is reached
        character(len=msglen), intent(out) :: errmsg  !! which limit, where the run stands
        integer(i8) :: now
        real(wp) :: wall, since
        stat = stat_ok
        errmsg = ''
        if (me%mode == progress_off .and. me%wall_limit <= zero .and. me%step_limit <= 0) return
        call system_clock(now)
        wall = real(now - me%c0, wp)/real(me%rate, wp)
        if (me%step_limit > 0 .and. nsteps >= me%step_limit) then
            stat = stat_step_failed
            write (errmsg, '(a,i0,a,a)') 'the step limit of ', me%step_limit, ' steps (RUNLIMIT card or '// &
                '--max-steps) was reached', where_now()
        else if (me%wall_limit > zero .and. wall >= me%wall_limit) then
            stat = stat_step_failed
            errmsg = 'the wall-time limit of '//seconds(me%wall_limit)//' s (RUNLIMIT card or '// &
                     '--max-wall) was reached'//where_now()
        end if
        if (me%mode == progress_off) return
        since = real(now - me%shown, wp)/real(me%rate, wp)
        if (me%tty) then
            if (wall < first_after .or. since < tty_every) return
        else
            if (since < log_every) return
        end if
        me%shown = now
        if (me%tty) then
            write (error_unit, '(a)', advance='no') achar(13)//line()//'   '
        else
            write (error_unit, '(a)') line()
        end if
        flush (error_unit)
        me%printed = .true.
    contains
        function line() result(s)
            character(len=:), allocatable :: s
            character(len=200) :: buf
            real(wp) :: frac
            frac = (t - me%t0)/max(me%t_end - me%t0, tiny(1.0_wp))
            write (buf, '(a,f10.5,a,f10.5,a,f5.1,a,f9.1,a,es9.2,a)') 'hhneck: t =', t, ' s of', me%t_end, ' s (', &
                100*frac, ' %), ', wall, ' s wall, step', h, ' s, '
            if (frac > 1.0e-6_wp) then
                s = trim(buf)//' about '//trim(duration(wall*(1 - frac)/frac))//' to go'
            else
                s = trim(buf)//' time to go not yet known'
            end if
        end function line
        function where_now() result(s)
            character(len=:), allocatable :: s
            s = ' at t = '//num(t, '(es11.4)')//' s of '//num(me%t_end, '(g0.4)')//' s, after '// &
                num(wall, '(f0.1)')//' s wall and '//num(real(nsteps, wp), '(i0)')//' steps (last step '// &
                num(h, '(es9.2)')//' s)'
        end function where_now
        function seconds(x) result(s)
            real(wp), intent(in) :: x
            character(len=:), allocatable :: s
            if (abs(x - nint(x)) < 1.0e-9_wp*max(1.0_wp, abs(x))) then
                s = num(x, '(i0)')
            else
                s = num(x, '(g0.4)')
            end if
        end function seconds
        function num(x, fmt) result(s)
            real(wp), intent(in) :: x
            character(len=*), intent(in) :: fmt
            character(len=:), allocatable :: s
            character(len=30) :: buf
            if (fmt == '(i0)') then
                write (buf, fmt) nint(x, i8)
            else
                write (buf, fmt) x
            end if
            s = trim(adjustl(buf))
            if (s(1:1) == '.') s = '0'//s
        end function num
    end subroutine progress_update

    !> End the progress line (on a terminal).
    subroutine progress_finish(me)
        class(progress_t), intent(inout) :: me
        if (me%printed .and. me%tty) then
            write (error_unit, '(a)') ''
            flush (error_unit)
        end if
        me%printed = .false.
    end subroutine progress_finish

    !> Steps a fixed-step method (RK4, ABM4) takes for the case's run, as
    !! a real number (it may exceed the integer range); 0 for the
    !! error-controlled methods, whose step count is not known in advance.
    pure real(wp) function fixed_steps(cs) result(n)
        type(case_t), intent(in) :: cs   !! the case (CONTROL card: span, step, integrator)
        n = zero
        if (cs%integrator /= 'RK4' .and. cs%integrator /= 'ABM4') return
        n = real(ceiling((cs%t_end - cs%t_start)/cs%h*(1 - 1.0e-12_wp), i8), wp)
    end function fixed_steps

    !> A run that cannot finish, named before it starts: a fixed-step run
    !! of more steps than the step limit (RUNLIMIT card or --max-steps) is
    !! refused (stat_bad_input, located at the CONTROL card's step);
    !! one of more than 1E6 steps gets a warning with the step and
    !! evaluation count and the wall time they take at the cost of one
    !! dynamics evaluation measured now, in this build, on this machine.
    subroutine run_budget(cs, stat, errmsg, warning)
        type(case_t), intent(in) :: cs                 !! the case as it will run (limits from the command line included)
        integer, intent(out) :: stat                   !! stat_ok, or stat_bad_input beyond the step limit
        character(len=msglen), intent(out) :: errmsg   !! the refusal, located at the CONTROL card
        character(len=msglen), intent(out) :: warning  !! '' or the warning of a long fixed-step run
        real(wp) :: n, evals, t_eval, wall
        character(len=200) :: buf
        stat = stat_ok
        errmsg = ''
        warning = ''
        n = fixed_steps(cs)
        if (n <= zero) return
        if (cs%step_limit > 0 .and. n > cs%step_limit) then
            stat = stat_bad_input
            write (buf, '(a,es9.2,a,i0,a,es9.2,a)') ' takes ', n, ' fixed steps for the run, more than its step '// &
                'limit of ', cs%step_limit, ' (RUNLIMIT card or --max-steps); expected a step of at least ', &
                (cs%t_end - cs%t_start)/cs%step_limit, ' s, a higher step limit, or an error-controlled method'
            errmsg = trim(cs%control_at)//': '//trim(cs%integrator)//trim(buf)
            return
        end if
        if (n <= many_steps) return
        evals = n*merge(4, 2, cs%integrator == 'RK4')      ! RK4: 4 per step; ABM4: PECE, 2 per step
        t_eval = evaluation_seconds(cs)
        wall = evals*t_eval
        write (buf, '(a,es9.2,a,es9.2,a,f0.1,a)') ' takes ', n, ' fixed steps and ', evals, &
            ' dynamics evaluations for the run: about '//duration(wall)//' of wall time at the ', t_eval*1.0e6_wp, &
            ' us per evaluation measured now'
        warning = trim(cs%control_at)//': '//trim(cs%integrator)//trim(buf)
        if (cs%wall_limit > zero .and. wall > cs%wall_limit) then
            warning = trim(warning)//'; its wall-time limit of '//duration(cs%wall_limit)//' stops it first'
        else
            warning = trim(warning)//'; expected at most 1E6 steps: a longer step, an error-controlled '// &
                      'method (ROS34PW2), or a RUNLIMIT card'
        end if
    end subroutine run_budget

    !> Wall time [s] of one dynamics evaluation of the case's model at its
    !! initial state: the median of 15 rounds of a few evaluations.
    function evaluation_seconds(cs) result(t_eval)
        type(case_t), intent(in) :: cs
        real(wp) :: t_eval
        integer, parameter :: rounds = 15, per_round = 4
        type(dyn_workspace_t) :: ws
        real(wp), allocatable :: xf(:), xdf(:), xddf(:)
        real(wp) :: times(rounds)
        integer(i8) :: c0, c1, rate
        integer :: r, k, st
        integer, allocatable :: idx(:)
        character(len=msglen) :: m
        call dynamics_setup(cs%model, ws)
        xf = cs%x0(ws%ifree)
        xdf = cs%xd0(ws%ifree)
        allocate (xddf(ws%nfree))
        do r = 1, rounds
            call system_clock(c0, rate)
            do k = 1, per_round
                call dynamics_evaluate(cs%model, ws, cs%t_start, xf, xdf, xddf, st, m)
            end do
            call system_clock(c1)
            times(r) = real(c1 - c0, wp)/real(rate, wp)/per_round
        end do
        idx = sort_index(times)
        t_eval = times(idx((rounds + 1)/2))
    end function evaluation_seconds

    !> "12 s", "3.5 min", "2.1 h", "4.0 days".
    function duration(s) result(txt)
        real(wp), intent(in) :: s
        character(len=:), allocatable :: txt
        character(len=20) :: buf
        if (s < 120.0_wp) then
            write (buf, '(i0,a)') nint(s), ' s'
        else if (s < 7200.0_wp) then
            write (buf, '(f6.1,a)') s/60, ' min'
        else if (s < 172800.0_wp) then
            write (buf, '(f6.1,a)') s/3600, ' h'
        else
            write (buf, '(es9.2,a)') s/86400, ' days'
        end if
        txt = trim(adjustl(buf))
    end function duration

    !> Why a run that hit a limit is slow: the fastest mode of the Jacobian
    !! at the last good state against the step size. When h |lambda| is of
    !! order one, the step is held down by stability (a stiff model): an
    !! implicit method or a softer model helps; otherwise by accuracy.
    function limit_diagnosis(sys, t, y, h, integrator) result(s)
        type(model_ode_t), intent(inout) :: sys     !! the model's ODE system
        real(wp), intent(in) :: t                   !! time of the last good state [s]
        real(wp), intent(in) :: y(:)                !! last good state (x_F, xdot_F, E)
        real(wp), intent(in) :: h                   !! last step size [s]
        character(len=*), intent(in) :: integrator  !! method name (CONTROL F4)
        character(len=:), allocatable :: s
        real(wp) :: rho
        integer :: lead, st, nf
        character(len=msglen) :: m
        character(len=400) :: buf
        s = ''
        call spectral_radius(sys, t, y, rho, lead, st, m)
        if (st /= 0 .or. .not. (rho > zero)) return
        nf = sys%ws%nfree
        write (buf, '(a,es9.2,3a,es9.2,a)') '. The fastest mode has |lambda| =', rho, ' 1/s, mostly in ', &
            trim(dof_label(sys%model%tree, sys%ws%ifree(1 + mod(lead - 1, nf)))), ' (h |lambda| =', h*rho, ')'
        s = trim(buf)
        if (h*rho > 0.3_wp .and. (trim(integrator) == 'ROS2' .or. trim(integrator) == 'ROS34PW2')) then
            s = s//': '//trim(integrator)//' is stable there; accuracy with a stiff mode sets its step. '// &
                remedy(integrator, sys%model%solver, sys%model%jacobian, held_by_stiffness, &
                       trim(dof_label(sys%model%tree, sys%ws%ifree(1 + mod(lead - 1, nf)))))
        else if (h*rho > 0.3_wp) then
            s = s//': the step is held down by stiffness, not accuracy ('//trim(integrator)//' is explicit). '// &
                remedy(integrator, sys%model%solver, sys%model%jacobian, held_by_stiffness, &
                       trim(dof_label(sys%model%tree, sys%ws%ifree(1 + mod(lead - 1, nf)))))
        else
            s = s//': the step is limited by accuracy, not stability ('//trim(integrator)//'). '// &
                remedy(integrator, sys%model%solver, sys%model%jacobian, held_by_accuracy, '')
        end if
    end function limit_diagnosis

    !> The remedy of a run too slow to finish, for the run's own method:
    !! "Remedy: ..." naming what to change (CONTROL F4, --rtol, SOLVER,
    !! the stiff coordinate's element, LOCK or SCENE). A run held down by
    !! stiffness on an explicit method is pointed to ROS34PW2; one already on
    !! ROS2 to ROS34PW2, which keeps its Jacobian over many steps; one on
    !! ROS34PW2 to a looser tolerance, the stiff coordinate's element or its
    !! removal, and the structured Jacobian or a faster solver when the run
    !! has the slower one. A run held down by accuracy: a longer step for
    !! RK4 and ABM4, a looser tolerance for the error-controlled methods.
    pure function remedy(integrator, solver, jacobian, cause, dof) result(s)
        character(len=*), intent(in) :: integrator  !! the run's method (CONTROL F4)
        integer, intent(in) :: solver               !! the run's solver code (SOLVER F1, hn_linsolve)
        character(len=*), intent(in) :: jacobian    !! the stiff methods' Jacobian (SOLVER F2): STRUCT or FD
        integer, intent(in) :: cause                !! held_by_stiffness or held_by_accuracy
        character(len=*), intent(in) :: dof         !! the coordinate of the fastest mode ('' if not known)
        character(len=:), allocatable :: s, element, faster
        element = 'a softer element on that coordinate (STIFFEN or its card)'
        if (len_trim(dof) > 0) element = 'a softer element on '//trim(dof)//' (STIFFEN or its card)'
        faster = ''
        if (solver == solver_gauss) faster = ', SOLVER CHOLESKY or ABA (faster than GAUSS)'
        select case (trim(integrator))
        case ('ROS34PW2')
            if (cause == held_by_stiffness) then
                s = 'Remedy: a looser tolerance (--rtol), '//element//', or '// &
                    trim(merge_text(dof, 'that coordinate'))//' out of the model (LOCK, SCENE SAGITTAL)'
            else
                s = 'Remedy: a looser tolerance (--rtol), or fewer discontinuities in the inputs'
            end if
            if (trim(jacobian) == 'FD') s = s//', SOLVER F2 STRUCT (no differenced Jacobian)'
        case ('ROS2')
            if (cause == held_by_stiffness) then
                s = 'Remedy: ROS34PW2 (CONTROL F4; it keeps its Jacobian), a looser tolerance (--rtol), or '//element
            else
                s = 'Remedy: a looser tolerance (--rtol), or ROS34PW2 (CONTROL F4, order 3)'
            end if
        case ('RK4', 'ABM4')
            if (cause == held_by_stiffness) then
                s = 'Remedy: the stiff ROS34PW2 (CONTROL F4), or '//element
            else
                s = 'Remedy: a longer step (CONTROL F2), or an error-controlled method (DOPRI5; ROS34PW2 if stiff)'
            end if
        case default   ! DOPRI5, ADAMS: explicit, error-controlled
            if (cause == held_by_stiffness) then
                s = 'Remedy: the stiff ROS34PW2 (CONTROL F4), or '//element
            else
                s = 'Remedy: a looser tolerance (--rtol), or fewer discontinuities in the inputs'
            end if
        end select
        s = s//faster
    contains
        pure function merge_text(text, otherwise) result(r)
            character(len=*), intent(in) :: text, otherwise
            character(len=:), allocatable :: r
            r = trim(text)
            if (len(r) == 0) r = otherwise
        end function merge_text
    end function remedy

    !> The advice added to an integrator's stop message (`msg`) for the
    !! run's method: the step fell below its minimum (an explicit method on a
    !! stiff deck: ROS34PW2; a stiff method: a looser tolerance, an
    !! undeclared discontinuity), or the iteration matrix of a Rosenbrock
    !! method is singular (a shorter first step, the other Jacobian). ''
    !! for any other message.
    pure function stop_remedy(integrator, jacobian, msg) result(s)
        character(len=*), intent(in) :: integrator  !! the run's method (CONTROL F4)
        character(len=*), intent(in) :: jacobian    !! the stiff methods' Jacobian (SOLVER F2): STRUCT or FD
        character(len=*), intent(in) :: msg         !! the stop message
        character(len=:), allocatable :: s
        s = ''
        if (index(msg, 'the step fell below') > 0) then
            select case (trim(integrator))
            case ('ROS2', 'ROS34PW2')
                s = ' ('//trim(integrator)//', a stiff method). Remedy: a looser tolerance (--rtol), or EVENTS '// &
                    'STATE if an element switches there'
            case default
                s = ' ('//trim(integrator)//', explicit). Remedy: the stiff ROS34PW2 (CONTROL F4), or a looser '// &
                    'tolerance (--rtol)'
            end select
        else if (index(msg, 'iteration matrix') > 0) then
            s = '. Remedy: a shorter first step (CONTROL F2) or a tighter tolerance, or '
            if (trim(jacobian) == 'FD') then
                s = s//'the structured Jacobian (SOLVER F2 STRUCT)'
            else
                s = s//'a differenced Jacobian (SOLVER F2 FD)'
            end if
        end if
    end function stop_remedy

end module hn_progress
