!> Static equilibria (the STATICS card, hn_statics_card): at each load
!! level -- a load time t at which the applied tables, the prescribed
!! coordinates and the activations are taken -- the free coordinates x_F
!! where the generalized forces vanish with every rate zero,
!!
!!   r(x_F) = f_F(t, x_F, xdot = 0) = 0,
!!
!! the elements' elastic loads, gravity and the applied loads in balance.
!! Newton's method with the elements' generalized stiffness K of the
!! structured Jacobian (hn_jacobian): dr/dx_F ~ -K_FF, so the step solves
!! K_FF dx = r; a halving line search on |r|; when K's step does not
!! reduce |r| (or |r| falls by less than half), the next steps use the
!! exact Jacobian by central differences of r (K leaves out the geometric
!! stiffness, gravity's and the applied loads' dependence on x). The
!! levels are solved in order, each from the previous equilibrium
!! (continuation); a level Newton does not reach is approached through
!! intermediate load times (the interval halved, up to max_split times).
!!
!! At rest every rate term is zero: the discs' and springs' viscous terms,
!! the joint-limit dampers (rate only, one way) and the muscles'
!! force-velocity term contribute nothing; an element whose load depends
!! on its history (hysteresis) cannot be represented (docs/deck-format.md,
!! STATICS).
module hn_statics
    use hn_kinds, only: wp, zero, one, msglen, i8
    use hn_status, only: stat_ok, stat_singular, stat_not_finite, stat_step_failed
    use hn_model, only: model_t
    use hn_tree, only: dof_label
    use hn_dynamics, only: dyn_workspace_t, dynamics_setup, state_to_coordinates, dynamics_outputs, &
                           energy_terms, energy_t, nenergy
    use hn_kinematics, only: body_kinematics
    use hn_forces, only: compute_loads
    use hn_recursive, only: f_recursive
    use hn_jacobian, only: generalized_tangent
    use hn_linsolve, only: linear_solve, solver_gauss
    use hn_case, only: case_t
    use hn_channels, only: channel_set_t, channels_define, channels_compute, channels_start
    use hn_results, only: results_t
    use hn_listing, only: listing_t
    use hn_version, only: code_version
    use hn_run, only: run_result_t, exit_ok, exit_deck, exit_diverged, exit_output
    implicit none
    private

    public :: statics_options_t, statics_counts_t, statics_residual, statics_solve, statics_level, statics_execute

    !> Convergence and robustness settings of the equilibrium solve.
    type :: statics_options_t
        real(wp) :: step_tol = 1.0e-10_wp   !! converged: the Newton step max |dx| below this [m, rad]
        integer :: max_iter = 50            !! Newton iterations of one level before it counts as not reached
        integer :: max_halve = 20           !! halvings of the line search
        integer :: max_split = 12           !! halvings of a level's load interval (continuation)
        real(wp) :: fd_step = 1.0e-7_wp     !! difference step of the exact Jacobian [m, rad]
        real(wp) :: force_zero = 1.0e-14_wp !! a start whose |r| is below this is an equilibrium already [N, N m]
    end type statics_options_t

    !> Work counts of the solves.
    type :: statics_counts_t
        integer :: residuals = 0     !! evaluations of r (the dynamics evaluation without a_ij)
        integer :: tangents = 0      !! K of the elements formed
        integer :: fd_jacobians = 0  !! exact Jacobians by differences
        integer :: iterations = 0    !! Newton iterations
        integer :: splits = 0        !! intermediate load levels inserted
    end type statics_counts_t

contains

    !> The generalized forces of the free coordinates at rest, r = f_F(t,
    !! x_F, xdot = 0): kinematics, loads and f_i in ws.
    pure subroutine statics_residual(model, ws, t, xf, r)
        type(model_t), intent(in) :: model            !! the model
        type(dyn_workspace_t), intent(inout) :: ws    !! from dynamics_setup; out: this evaluation
        real(wp), intent(in) :: t                     !! load time [s]
        real(wp), intent(in) :: xf(:)                 !! free coordinates [m, rad]
        real(wp), intent(out) :: r(:)                 !! f_F [N, N m]
        real(wp) :: zf(size(xf))
        integer :: i
        zf = zero
        call state_to_coordinates(model, ws, t, xf, zf)
        ws%xd = zero
        ws%xdd = zero
        call body_kinematics(model%tree, ws%x, ws%xd, ws%kin)
        call compute_loads(model, t, ws%kin, ws%x, ws%xd, ws%loads, ws%eo)
        call f_recursive(model%tree, ws%kin, ws%loads, ws%f)
        do i = 1, ws%nfree
            r(i) = ws%f(ws%ifree(i))
        end do
    end subroutine statics_residual

    !> The equilibrium at load time t by Newton's method from xf (module
    !! doc). On failure xf is left at the start value and errmsg says
    !! where and why (no NaN is returned).
    subroutine statics_solve(model, ws, t, xf, opt, cnt, stat, errmsg)
        type(model_t), intent(in) :: model             !! the model
        type(dyn_workspace_t), intent(inout) :: ws     !! from dynamics_setup
        real(wp), intent(in) :: t                      !! load time [s]
        real(wp), intent(inout) :: xf(:)               !! in: the start; out: the equilibrium [m, rad]
        type(statics_options_t), intent(in) :: opt     !! tolerances and limits
        type(statics_counts_t), intent(inout) :: cnt   !! work counts, incremented
        integer, intent(out) :: stat                   !! stat_ok, stat_singular, stat_not_finite or stat_step_failed
        character(len=msglen), intent(out) :: errmsg   !! load time, failure, coordinate ('' when stat_ok)
        real(wp) :: x(size(xf)), xt(size(xf)), r(size(xf)), rt(size(xf)), dx(size(xf)), jac(size(xf), size(xf))
        real(wp) :: kgen(ws%ndof, ws%ndof), cgen(ws%ndof, ws%ndof), rn, rnt, alpha
        integer :: it, ls, row, n, i, j
        logical :: exact, accepted
        n = size(xf)
        errmsg = ''
        stat = stat_ok
        if (n == 0) return
        x = xf
        call residual(x, r, rn)
        if (stat /= stat_ok .or. rn <= opt%force_zero) return   ! the start is at rest already
        exact = .false.
        do it = 1, opt%max_iter
            cnt%iterations = cnt%iterations + 1
            if (exact) then
                call fd_jacobian()
                if (stat /= stat_ok) return
            else
                call statics_residual(model, ws, t, x, rt)   ! the kinematics of x for K
                cnt%residuals = cnt%residuals + 1
                call generalized_tangent(model, ws%kin, t, ws%x, ws%xd, kgen, cgen)
                cnt%tangents = cnt%tangents + 1
                do j = 1, n
                    do i = 1, n
                        jac(i, j) = kgen(ws%ifree(i), ws%ifree(j))
                    end do
                end do
            end if
            dx = r
            call linear_solve(solver_gauss, jac, dx, stat, errmsg, row)
            if (stat /= stat_ok .and. stat /= stat_singular) stat = stat_ok   ! ill-conditioned: dx still usable
            if (stat /= stat_ok .or. .not. all(abs(dx) <= huge(one))) then
                if (.not. exact) then
                    exact = .true.
                    stat = stat_ok
                    cycle
                end if
                stat = stat_singular
                write (errmsg, '(a,es12.5,3a)') 'STATICS at load time ', t, ' s: the stiffness is singular at '// &
                    'coordinate ', trim(dof_label(model%tree, ws%ifree(max(1, min(row, n))))), &
                    ' (no element or load holds it)'
                return
            end if
            if (maxval(abs(dx)) <= opt%step_tol) then
                xf = x + dx
                return
            end if
            alpha = one
            accepted = .false.
            do ls = 0, opt%max_halve
                xt = x + alpha*dx
                call residual(xt, rt, rnt)
                if (stat /= stat_ok) then
                    stat = stat_ok           ! a non-finite trial: a shorter step
                else if (rnt <= (one - 1.0e-4_wp*alpha)*rn) then
                    accepted = .true.
                    exit
                end if
                alpha = 0.5_wp*alpha
            end do
            if (.not. accepted) then
                if (.not. exact) then
                    exact = .true.
                    cycle
                end if
                stat = stat_step_failed
                write (errmsg, '(a,es12.5,a,es10.3,3a)') 'STATICS at load time ', t, &
                    ' s: no equilibrium found (the line search cannot reduce the residual ', rn, &
                    ' N or N m; largest at coordinate ', trim(dof_label(model%tree, ws%ifree(maxloc(abs(r), 1)))), ')'
                return
            end if
            if (rnt > 0.5_wp*rn .or. alpha < one) exact = .true.   ! K's steps contract slowly here
            x = xt
            r = rt
            rn = rnt
        end do
        stat = stat_step_failed
        write (errmsg, '(a,es12.5,a,i0,a,es10.3,3a)') 'STATICS at load time ', t, ' s: no equilibrium after ', &
            opt%max_iter, ' Newton iterations (residual ', rn, ' N or N m, largest at coordinate ', &
            trim(dof_label(model%tree, ws%ifree(maxloc(abs(r), 1)))), ')'
    contains
        subroutine residual(xx, rr, norm)
            real(wp), intent(in) :: xx(:)
            real(wp), intent(out) :: rr(:), norm
            call statics_residual(model, ws, t, xx, rr)
            cnt%residuals = cnt%residuals + 1
            norm = norm2(rr)
            if (.not. (norm <= huge(one))) then
                stat = stat_not_finite
                write (errmsg, '(a,es12.5,a)') 'STATICS at load time ', t, ' s: the generalized forces are not finite'
            end if
        end subroutine residual
        !> jac = -dr/dx by central differences (the sign of K).
        subroutine fd_jacobian()
            real(wp) :: xp(n), rp(n), rm(n), h
            integer :: jj
            cnt%fd_jacobians = cnt%fd_jacobians + 1
            do jj = 1, n
                h = opt%fd_step*max(one, abs(x(jj)))
                xp = x
                xp(jj) = x(jj) + h
                call statics_residual(model, ws, t, xp, rp)
                xp(jj) = x(jj) - h
                call statics_residual(model, ws, t, xp, rm)
                cnt%residuals = cnt%residuals + 2
                jac(:, jj) = -(rp - rm)/(2*h)
            end do
        end subroutine fd_jacobian
    end subroutine statics_solve

    !> The equilibrium at load time t continued from the equilibrium xf at
    !! load time t_prev: Newton from xf; where it fails, the load interval is
    !! halved and the intermediate levels solved first (up to opt%max_split
    !! halvings). On failure xf is the last equilibrium reached.
    subroutine statics_level(model, ws, t_prev, t, xf, opt, cnt, stat, errmsg)
        type(model_t), intent(in) :: model             !! the model
        type(dyn_workspace_t), intent(inout) :: ws     !! from dynamics_setup
        real(wp), intent(in) :: t_prev                 !! load time of xf [s]
        real(wp), intent(in) :: t                      !! load time of the level [s]
        real(wp), intent(inout) :: xf(:)               !! in: the equilibrium at t_prev; out: at t [m, rad]
        type(statics_options_t), intent(in) :: opt     !! tolerances and limits
        type(statics_counts_t), intent(inout) :: cnt   !! work counts, incremented
        integer, intent(out) :: stat                   !! stat_ok or statics_solve's failure at the finest split
        character(len=msglen), intent(out) :: errmsg   !! the failure ('' when stat_ok)
        real(wp) :: ta, dt
        integer :: depth
        character(len=msglen) :: inner
        ta = t_prev
        dt = t - t_prev
        depth = 0
        do
            call statics_solve(model, ws, ta + dt, xf, opt, cnt, stat, errmsg)
            if (stat == stat_ok) then
                ta = ta + dt
                if (abs(t - ta) <= 1.0e-12_wp*max(one, abs(t))) return
                dt = min(2*dt, t - ta)        ! back to longer intervals once through
                if (dt /= t - ta) cnt%splits = cnt%splits + 1
                depth = max(depth - 1, 0)
            else
                depth = depth + 1
                if (depth > opt%max_split .or. dt == zero) then
                    inner = errmsg
                    write (errmsg, '(a,es12.5,a,es12.5,2a)') 'STATICS: load time ', t, ' s not reached (equilibrium '// &
                        'at ', ta, ' s); ', trim(inner)
                    return
                end if
                dt = 0.5_wp*dt
                cnt%splits = cnt%splits + 1
            end if
        end do
    end subroutine statics_level

    !> The STATICS run of a case: the listing header and deck, one
    !! equilibrium per level of cs%statics_times (each continued from the
    !! previous one, the first from the deck's initial coordinates), each
    !! a sample of the result file with every channel (the "time" axis is
    !! the level's load time), a table of the levels and the counts in the
    !! listing. A level not reached stops the run (exit 3, the file marked
    !! incomplete with the levels reached).
    subroutine statics_execute(cs, lu, h5name, res)
        type(case_t), intent(in) :: cs                !! the case (statics_times allocated)
        integer, intent(in) :: lu                     !! listing unit
        character(len=*), intent(in) :: h5name        !! result file name ('' for none)
        type(run_result_t), intent(out) :: res        !! what happened
        type(dyn_workspace_t) :: ws
        type(channel_set_t) :: ch
        type(results_t) :: out
        type(listing_t) :: lst
        type(energy_t) :: en
        type(statics_options_t) :: opt
        type(statics_counts_t) :: cnt
        real(wp), allocatable :: xf(:), zf(:)
        real(wp) :: t_prev, eq(nenergy)
        integer :: stat, k, it0, st
        integer(i8) :: c0, c1, rate
        character(len=msglen) :: msg, line, note
        call system_clock(c0, rate)
        if (allocated(cs%subtitles)) then
            call lst%start(lu, cs%model%title, code_version, cs%subtitles)
        else
            call lst%start(lu, cs%model%title, code_version)
        end if
        call lst%echo_deck(cs%deck)
        if (cs%hold_posture .or. cs%hold_prestrain) then
            call stop_with(exit_deck, 'failed', 'STATICS: a HOLD card holds the start posture of a dynamic run; '// &
                           'a static solve takes no HOLD card (remove one of them)')
            call lst%message('RUN NOT STARTED: '//trim(res%message))
            return
        end if
        call lst%model_summary(cs)
        call channels_define(cs, ch)
        call dynamics_setup(cs%model, ws)
        xf = cs%x0(ws%ifree)
        allocate (zf(ws%nfree))
        zf = zero
        eq = zero
        call dynamics_outputs(cs%model, ws, cs%statics_times(1), xf, zf, stat, zf)
        en = energy_terms(cs%model, ws, eq)
        ch%e0 = en%total
        call channels_start(cs, ws, ch)
        if (len_trim(h5name) > 0) then
            call out%open(cs, ch, trim(h5name), code_version, stat, msg, res%file_note)
            if (stat /= stat_ok) then
                call stop_with(exit_output, 'failed', msg)
                return
            end if
        end if
        call lst%put('')
        call lst%put(' STATIC EQUILIBRIA (STATICS): LEVEL, LOAD TIME (S), NEWTON ITERATIONS')
        t_prev = cs%statics_times(1)
        do k = 1, size(cs%statics_times)
            it0 = cnt%iterations
            call statics_level(cs%model, ws, t_prev, cs%statics_times(k), xf, opt, cnt, stat, msg)
            if (stat /= stat_ok) then
                call stop_with(exit_diverged, 'incomplete', msg)
                exit
            end if
            t_prev = cs%statics_times(k)
            call dynamics_outputs(cs%model, ws, t_prev, xf, zf, stat, zf)
            en = energy_terms(cs%model, ws, eq)
            call channels_compute(cs, ws, t_prev, en, ch)
            call out%sample(t_prev, ch, ws)
            if (out%failed()) then
                call stop_with(exit_output, 'incomplete', out%error())
                exit
            end if
            res%t_reached = t_prev
            res%nsteps = res%nsteps + 1
            write (line, '(i8,es14.5,i6)') k, t_prev, cnt%iterations - it0
            call lst%put(trim(line))
        end do
        call system_clock(c1)
        res%wall = real(c1 - c0, wp)/real(rate, wp)
        res%nevals = cnt%residuals
        res%njac = cnt%tangents + cnt%fd_jacobians
        res%nfact = cnt%iterations
        write (line, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,i0,a,i0,a,f8.3,a)') 'END OF STATICS: ', res%nsteps, ' OF ', &
            size(cs%statics_times), ' LEVELS, ', cnt%iterations, ' NEWTON ITERATIONS, ', cnt%residuals, &
            ' EVALUATIONS, ', cnt%tangents, ' TANGENTS, ', cnt%fd_jacobians, ' DIFFERENCE JACOBIANS, ', &
            cnt%splits, ' INTERMEDIATE LEVELS, ', res%wall, ' S WALL TIME'
        call lst%message(line)
        if (res%exit_code /= exit_ok) call lst%message('RUN INCOMPLETE: '//trim(res%message))
        call out%close(ch, trim(res%status), trim(res%message), st, line, note)
        if (st /= stat_ok .and. res%exit_code == exit_ok) call stop_with(exit_output, 'incomplete', line)
        if (len_trim(note) > 0) res%file_note = note
    contains
        subroutine stop_with(code, status, message)
            integer, intent(in) :: code
            character(len=*), intent(in) :: status, message
            res%exit_code = code
            res%status = status
            res%message = message
        end subroutine stop_with
    end subroutine statics_execute

end module hn_statics
