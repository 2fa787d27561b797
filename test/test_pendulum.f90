!> Pendulums against closed forms: compound-pendulum periods (small
!! amplitude and the elliptic-integral value), double-pendulum and
!! moving-support accelerations against Lagrange's equations by hand.
program test_pendulum
    use hn_kinds, only: wp, zero, one, pi, g_std, msglen, deg
    use hn_tree, only: body_tree_t
    use hn_model, only: model_t, model_init
    use hn_dynamics, only: dyn_workspace_t, dynamics_setup, dynamics_evaluate, model_ode_t, model_ode_init
    use hn_integrators, only: dopri5_t
    use hn_motion, only: motion_harmonic, motion_constant
    use hn_testing, only: test_suite_t
    use hn_test_models, only: rng_t, pendulum_tree, elliptic_k
    implicit none

    ! compound pendulum: mass m, centroidal inertia ic, pivot c above the mass centre
    real(wp), parameter :: m = 2.5_wp, ic = 0.04_wp, c = 0.3_wp
    type(test_suite_t) :: suite

    call test_small_amplitude_period()
    call test_large_amplitude_period()
    call test_double_pendulum_lagrange()
    call test_prescribed_support_lagrange()
    call test_prescribed_constant_equals_locked()
    call suite%finish()

contains

    !> Period of the compound pendulum released at rest from theta0, from
    !! the times of two successive downward zero crossings of theta, each
    !! refined by Newton steps on a re-integration.
    real(wp) function measured_period(theta0) result(period)
        real(wp), intent(in) :: theta0
        type(model_ode_t) :: sys
        type(model_t) :: model
        type(body_tree_t) :: tree
        type(dopri5_t) :: integ
        real(wp) :: t, y(6), tprev, yprev(6), tc(3), dt
        integer :: stat, ncross
        character(len=msglen) :: msg
        call pendulum_tree(tree, [m], [ic], [c], [one])
        call model_init(model, tree)
        call model_ode_init(sys, model)
        call integ%set_tolerances(1.0e-12_wp, 1.0e-14_wp); call integ%set_step(1.0e-3_wp)
        t = zero; y = zero; y(1) = theta0
        call integ%init(sys, t, y, stat, msg)
        dt = 1.0e-2_wp
        ncross = 0
        do while (ncross < 3)
            tprev = t; yprev = y
            call integ%advance(sys, t + dt, y, huge(one), stat, msg)
            t = t + dt
            if (stat /= 0) error stop trim(msg)
            if (sign(one, y(1)) /= sign(one, yprev(1))) then
                ncross = ncross + 1
                tc(ncross) = refine_crossing(sys, tprev, yprev, t, y)
            end if
        end do
        period = tc(3) - tc(1)
    end function measured_period

    !> Time where theta = 0 between (t0, y0) and (t1, y1), by Newton's method
    !! with theta' from the state and re-integration from t0.
    real(wp) function refine_crossing(sys, t0, y0, t1, y1) result(tz)
        type(model_ode_t), intent(inout) :: sys
        real(wp), intent(in) :: t0, y0(6), t1, y1(6)
        type(dopri5_t) :: integ
        real(wp) :: y(6)
        integer :: it, stat
        character(len=msglen) :: msg
        tz = t0 - y0(1)*(t1 - t0)/(y1(1) - y0(1))
        do it = 1, 6
            call integ%set_tolerances(1.0e-13_wp, 1.0e-15_wp); call integ%set_step(1.0e-4_wp)
            call integ%init(sys, t0, y0, stat, msg)
            call integ%advance(sys, tz, y, tz, stat, msg)
            tz = tz - y(1)/y(2)
            if (abs(y(1)) < 1.0e-14_wp) exit
        end do
    end function refine_crossing

    subroutine test_small_amplitude_period()
        real(wp) :: t0, tm, theta0
        theta0 = 0.01_wp
        t0 = 2*pi*sqrt((ic + m*c**2)/(m*g_std*c))
        tm = measured_period(theta0)
        ! the exact period exceeds 2 pi sqrt(I/mgc) by theta0^2/16 relative
        call suite%near(tm/t0, one + theta0**2/16, 1.0e-8_wp, &
                        'compound pendulum small-amplitude period = 2 pi sqrt(I_O/(m g c)) (1 + theta0^2/16)')
    end subroutine test_small_amplitude_period

    subroutine test_large_amplitude_period()
        real(wp) :: tex, tm, theta0
        theta0 = 150*deg
        tex = 4*sqrt((ic + m*c**2)/(m*g_std*c))*elliptic_k(sin(theta0/2))
        tm = measured_period(theta0)
        call suite%near(tm/tex, one, 1.0e-8_wp, &
                        'compound pendulum period at 150 deg = 4 sqrt(I_O/(m g c)) K(sin(theta0/2))')
    end subroutine test_large_amplitude_period

    !> Double pendulum with relative angles (theta1, theta2); by hand in the
    !! absolute angles phi1 = theta1, phi2 = theta1 + theta2:
    !!  M11 phi1'' + M12 phi2'' + m2 L1 c2 sin(phi1-phi2) phi2'^2 + (m1 c1 + m2 L1) g sin phi1 = 0
    !!  M12 phi1'' + M22 phi2'' - m2 L1 c2 sin(phi1-phi2) phi1'^2 + m2 c2 g sin phi2 = 0
    !! M11 = I1 + m1 c1^2 + m2 L1^2, M12 = m2 L1 c2 cos(phi1-phi2), M22 = I2 + m2 c2^2.
    subroutine test_double_pendulum_lagrange()
        real(wp), parameter :: m1 = 1.7_wp, m2 = 0.9_wp, i1 = 0.03_wp, i2 = 0.011_wp, &
                               c1 = 0.21_wp, c2 = 0.17_wp, l1 = 0.45_wp
        type(body_tree_t) :: tree
        type(model_t) :: model
        type(dyn_workspace_t) :: ws
        type(rng_t) :: rng
        real(wp) :: th(2), thd(2), thdd(2), p1, p2, p1d, p2d, mm(2, 2), r(2), pdd(2), det, err
        integer :: itrial, stat
        character(len=msglen) :: msg
        call pendulum_tree(tree, [m1, m2], [i1, i2], [c1, c2], [l1, one])
        call model_init(model, tree)
        call dynamics_setup(model, ws)
        err = zero
        do itrial = 1, 10
            th = [rng%uniform(-pi, pi), rng%uniform(-pi, pi)]
            thd = [rng%uniform(-5.0_wp, 5.0_wp), rng%uniform(-5.0_wp, 5.0_wp)]
            call dynamics_evaluate(model, ws, zero, th, thd, thdd, stat, msg)
            p1 = th(1); p2 = th(1) + th(2); p1d = thd(1); p2d = thd(1) + thd(2)
            mm(1, 1) = i1 + m1*c1**2 + m2*l1**2
            mm(1, 2) = m2*l1*c2*cos(p1 - p2)
            mm(2, 1) = mm(1, 2)
            mm(2, 2) = i2 + m2*c2**2
            r(1) = -m2*l1*c2*sin(p1 - p2)*p2d**2 - (m1*c1 + m2*l1)*g_std*sin(p1)
            r(2) = m2*l1*c2*sin(p1 - p2)*p1d**2 - m2*c2*g_std*sin(p2)
            det = mm(1, 1)*mm(2, 2) - mm(1, 2)**2
            pdd(1) = (mm(2, 2)*r(1) - mm(1, 2)*r(2))/det
            pdd(2) = (mm(1, 1)*r(2) - mm(1, 2)*r(1))/det
            err = max(err, abs(thdd(1) - pdd(1)), abs(thdd(2) - (pdd(2) - pdd(1))))
        end do
        call suite%near(err, zero, 1.0e-10_wp, 'double pendulum accelerations = Lagrange by hand (10 states)')
    end subroutine test_double_pendulum_lagrange

    !> Pendulum whose pivot moves along x as x_s = A sin(w t) (the root's
    !! x-translation prescribed): (I + m c^2) th'' - m c cos(th) x_s'' + m g c sin(th) = 0.
    subroutine test_prescribed_support_lagrange()
        real(wp), parameter :: amp = 0.03_wp, w = 17.0_wp
        type(body_tree_t) :: tree
        type(model_t) :: model
        type(dyn_workspace_t) :: ws
        type(rng_t) :: rng
        real(wp) :: th(1), thd(1), thdd(1), t, xsdd, expect, err
        integer :: itrial, stat
        character(len=msglen) :: msg
        call pendulum_tree(tree, [m], [ic], [c], [one])
        tree%active(1, 1) = .true.
        call rebuild(tree)
        call model_init(model, tree)
        model%prescribed(1) = .true.
        model%motion(1) = motion_harmonic(zero, amp, w, zero)
        call dynamics_setup(model, ws)
        err = zero
        do itrial = 1, 10
            t = rng%uniform(zero, one)
            th = rng%uniform(-pi, pi); thd = rng%uniform(-5.0_wp, 5.0_wp)
            call dynamics_evaluate(model, ws, t, th, thd, thdd, stat, msg)
            xsdd = -amp*w**2*sin(w*t)
            expect = (m*c*cos(th(1))*xsdd - m*g_std*c*sin(th(1)))/(ic + m*c**2)
            err = max(err, abs(thdd(1) - expect))
        end do
        call suite%near(err, zero, 1.0e-10_wp, 'pendulum on a prescribed moving support = Lagrange by hand')
    end subroutine test_prescribed_support_lagrange

    !> Prescribing the five other coordinates as constants gives the same
    !! motion as locking them.
    subroutine test_prescribed_constant_equals_locked()
        type(body_tree_t) :: tl, tp
        type(model_t) :: ml, mp
        type(dyn_workspace_t) :: wl, wpr
        real(wp) :: a1(1), a2(1)
        integer :: stat, j
        character(len=msglen) :: msg
        call pendulum_tree(tl, [m], [ic], [c], [one])
        tl%q_ref(4, 1) = 0.2_wp
        call rebuild(tl)
        tp = tl
        tp%active = .true.
        call rebuild(tp)
        call model_init(ml, tl)
        call model_init(mp, tp)
        do j = 1, 6
            if (j /= 5) then
                mp%prescribed(j) = .true.
                mp%motion(j) = motion_constant(tl%q_ref(j, 1))
            end if
        end do
        call dynamics_setup(ml, wl)
        call dynamics_setup(mp, wpr)
        call dynamics_evaluate(ml, wl, zero, [0.7_wp], [1.3_wp], a1, stat, msg)
        call dynamics_evaluate(mp, wpr, zero, [0.7_wp], [1.3_wp], a2, stat, msg)
        call suite%near(a2(1), a1(1), 1.0e-12_wp*abs(a1(1)), 'prescribed-constant coordinates act as locked ones')
    end subroutine test_prescribed_constant_equals_locked

    subroutine rebuild(tree)
        use hn_tree, only: tree_build
        type(body_tree_t), intent(inout) :: tree
        integer :: stat
        character(len=msglen) :: msg
        call tree_build(tree, stat, msg)
        if (stat /= 0) error stop trim(msg)
    end subroutine rebuild

end program test_pendulum
