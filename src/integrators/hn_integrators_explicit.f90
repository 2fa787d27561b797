!> RK4, ABM4 and DOPRI5: the explicit methods of hn_integrators.
submodule(hn_integrators) hn_integrators_explicit
    implicit none

contains

    !> One RK4 step of the fixed size (clipped to tstop).
    module procedure rk4_step
        real(wp), dimension(size(me%y)) :: k2, k3, k4, ynew, fnew
        real(wp) :: h
        h = clip_step(me%t, me%h, tstop)
        call rk4_formula(sys, me%t, me%y, me%f, h, ynew, k2, k3, k4, stat, errmsg)
        if (stat /= 0) return
        call sys%rhs(me%t + h, ynew, fnew, stat, errmsg)
        if (stat /= 0) return
        call accept(me, me%t + h, ynew, fnew)
    end procedure rk4_step

    !> One RK4 step of size h from (t, y) with f = g(t, y) given.
    subroutine rk4_formula(sys, t, y, f, h, ynew, k2, k3, k4, stat, errmsg)
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: t, y(:), f(:), h
        real(wp), intent(out) :: ynew(:), k2(:), k3(:), k4(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        call sys%rhs(t + half*h, y + half*h*f, k2, stat, errmsg); if (stat /= 0) return
        call sys%rhs(t + half*h, y + half*h*k2, k3, stat, errmsg); if (stat /= 0) return
        call sys%rhs(t + h, y + h*k3, k4, stat, errmsg); if (stat /= 0) return
        ynew = y + h/6.0_wp*(f + two*k2 + two*k3 + k4)
    end subroutine rk4_formula

    !> A restart forgets the history: the next steps start with RK4 again.
    module procedure abm4_reset_history
        me%nhist = 0
        if (.not. allocated(me%fh)) allocate (me%fh(size(me%y), 3))
    end procedure abm4_reset_history

    !> One ABM4 PECE step (RK4 while the history is short).
    module procedure abm4_step
        real(wp), dimension(size(me%y)) :: k2, k3, k4, yp, fp, yc, fc
        real(wp) :: h
        h = clip_step(me%t, me%h, tstop)
        if (h /= me%hhist) me%nhist = 0          ! history of another step size is useless
        me%hhist = h
        if (me%nhist < 3) then
            ! start (and restart) with RK4
            call rk4_formula(sys, me%t, me%y, me%f, h, yc, k2, k3, k4, stat, errmsg)
            if (stat /= 0) return
        else
            ! predict (Adams-Bashforth 4), evaluate, correct (Adams-Moulton 4), evaluate
            yp = me%y + h/24.0_wp*(55.0_wp*me%f - 59.0_wp*me%fh(:, 1) + 37.0_wp*me%fh(:, 2) - 9.0_wp*me%fh(:, 3))
            call sys%rhs(me%t + h, yp, fp, stat, errmsg)
            if (stat /= 0) return
            yc = me%y + h/24.0_wp*(9.0_wp*fp + 19.0_wp*me%f - 5.0_wp*me%fh(:, 1) + me%fh(:, 2))
        end if
        call sys%rhs(me%t + h, yc, fc, stat, errmsg)
        if (stat /= 0) return
        me%fh(:, 3) = me%fh(:, 2)
        me%fh(:, 2) = me%fh(:, 1)
        me%fh(:, 1) = me%f
        me%nhist = min(3, me%nhist + 1)
        call accept(me, me%t + h, yc, fc)
    end procedure abm4_step

    !> Dense-output coefficients cleared; the next step starts from h.
    module procedure dopri5_reset_history
        if (.not. allocated(me%rcont)) allocate (me%rcont(size(me%y), 5))
        me%rcont = zero
        me%rcont(:, 1) = me%y
        if (me%hnext <= zero) me%hnext = me%h
    end procedure dopri5_reset_history

    !> One accepted Dormand-Prince 5(4) step with error control.
    module procedure dopri5_step
        real(wp), parameter :: c2 = 1.0_wp/5, c3 = 3.0_wp/10, c4 = 4.0_wp/5, c5 = 8.0_wp/9
        real(wp), parameter :: a21 = 1.0_wp/5
        real(wp), parameter :: a31 = 3.0_wp/40, a32 = 9.0_wp/40
        real(wp), parameter :: a41 = 44.0_wp/45, a42 = -56.0_wp/15, a43 = 32.0_wp/9
        real(wp), parameter :: a51 = 19372.0_wp/6561, a52 = -25360.0_wp/2187, a53 = 64448.0_wp/6561, &
                               a54 = -212.0_wp/729
        real(wp), parameter :: a61 = 9017.0_wp/3168, a62 = -355.0_wp/33, a63 = 46732.0_wp/5247, &
                               a64 = 49.0_wp/176, a65 = -5103.0_wp/18656
        real(wp), parameter :: b1 = 35.0_wp/384, b3 = 500.0_wp/1113, b4 = 125.0_wp/192, &
                               b5 = -2187.0_wp/6784, b6 = 11.0_wp/84
        real(wp), parameter :: e1 = 71.0_wp/57600, e3 = -71.0_wp/16695, e4 = 71.0_wp/1920, &
                               e5 = -17253.0_wp/339200, e6 = 22.0_wp/525, e7 = -1.0_wp/40
        ! dense output of Shampine (1986)
        real(wp), parameter :: d1 = -12715105075.0_wp/11282082432.0_wp, d3 = 87487479700.0_wp/32700410799.0_wp, &
                               d4 = -10690763975.0_wp/1880347072.0_wp, d5 = 701980252875.0_wp/199316789632.0_wp, &
                               d6 = -1453857185.0_wp/822651844.0_wp, d7 = 69997945.0_wp/29380423.0_wp
        real(wp), dimension(size(me%y)) :: k1, k2, k3, k4, k5, k6, k7, ynew, ytmp
        real(wp) :: h, err, fac
        stat = 0; errmsg = ''
        k1 = me%f
        do
            h = clip_step(me%t, min(me%hnext, me%hmax), tstop)
            ytmp = me%y + h*a21*k1
            call sys%rhs(me%t + c2*h, ytmp, k2, stat, errmsg); if (stat /= 0) return
            ytmp = me%y + h*(a31*k1 + a32*k2)
            call sys%rhs(me%t + c3*h, ytmp, k3, stat, errmsg); if (stat /= 0) return
            ytmp = me%y + h*(a41*k1 + a42*k2 + a43*k3)
            call sys%rhs(me%t + c4*h, ytmp, k4, stat, errmsg); if (stat /= 0) return
            ytmp = me%y + h*(a51*k1 + a52*k2 + a53*k3 + a54*k4)
            call sys%rhs(me%t + c5*h, ytmp, k5, stat, errmsg); if (stat /= 0) return
            ytmp = me%y + h*(a61*k1 + a62*k2 + a63*k3 + a64*k4 + a65*k5)
            call sys%rhs(me%t + h, ytmp, k6, stat, errmsg); if (stat /= 0) return
            ynew = me%y + h*(b1*k1 + b3*k3 + b4*k4 + b5*k5 + b6*k6)
            call sys%rhs(me%t + h, ynew, k7, stat, errmsg); if (stat /= 0) return
            err = max(err_norm(me, h*(e1*k1 + e3*k3 + e4*k4 + e5*k5 + e6*k6 + e7*k7), me%y, ynew), err_floor)
            if (err <= one) exit
            me%nreject = me%nreject + 1
            me%hnext = h*max(fac_min, 0.9_wp*err**(-0.2_wp))
            if (me%hnext < me%hmin) then
                call step_too_small(me%t, me%hmin, stat, errmsg)
                return
            end if
        end do
        me%rcont(:, 1) = me%y
        me%rcont(:, 2) = ynew - me%y
        me%rcont(:, 3) = h*k1 - me%rcont(:, 2)
        me%rcont(:, 4) = me%rcont(:, 2) - h*k7 - me%rcont(:, 3)
        me%rcont(:, 5) = h*(d1*k1 + d3*k3 + d4*k4 + d5*k5 + d6*k6 + d7*k7)
        fac = min(fac_max, max(fac_min, 0.9_wp*err**(-0.2_wp)))
        if (h >= me%hnext*unclipped .or. fac < one) me%hnext = h*fac   ! a clipped step does not shrink hnext
        call accept(me, me%t + h, ynew, k7)
    end procedure dopri5_step

    !> Shampine's 4th-order dense output of the last step, and its derivative.
    module procedure dopri5_interpolate
        real(wp) :: s, s1, h
        if (at_current_point(me, tout, yout, dydt)) return
        h = me%t - me%told
        s = (tout - me%told)/h
        s1 = one - s
        yout = me%rcont(:, 1) + s*(me%rcont(:, 2) + s1*(me%rcont(:, 3) + s*(me%rcont(:, 4) + s1*me%rcont(:, 5))))
        if (present(dydt)) dydt = (me%rcont(:, 2) + (one - two*s)*me%rcont(:, 3) + s*(two - 3.0_wp*s)*me%rcont(:, 4) &
                                   + two*s*s1*(one - two*s)*me%rcont(:, 5))/h
    end procedure dopri5_interpolate

end submodule hn_integrators_explicit
