!> The linearly implicit methods of hn_integrators: ROS2 (Shampine &
!! Reichelt) and the Rosenbrock-W method ROS34PW2 (Rang & Angermann 2005).
!! Both solve with the iteration matrix I - hg J of hn_iteration_matrix.
submodule(hn_integrators) hn_integrators_rosenbrock
    implicit none

    ! ROS34PW2 in the classical form (Hairer & Wanner IV.7):
    !   (I - h gamma J) k_i = h g(t + alpha_i h, y + sum_j alpha_ij k_j) + h J sum_j gamma_ij k_j,
    !   y1 = y + sum b_i k_i, embedded yhat1 = y + sum bhat_i k_i,
    ! dense output y(t + theta h) = y + sum_i B_i(theta) k_i, B_i(theta) = sum_p bint(i,p) theta^p.
    integer, parameter :: ns = 4
    real(wp), parameter :: gam = 4.3586652150845900e-01_wp
    real(wp), parameter :: alpha_tab(ns, ns) = reshape([ &
        zero, 8.7173304301691801e-01_wp, 8.4457060015369423e-01_wp, zero, &
        zero, zero, -1.1299064236484185e-01_wp, zero, &
        zero, zero, zero, one, &
        zero, zero, zero, zero], [ns, ns])
    real(wp), parameter :: gamma_tab(ns, ns) = reshape([ &
        gam, -8.7173304301691801e-01_wp, -9.0338057013044082e-01_wp, 2.4212380706095346e-01_wp, &
        zero, gam, 5.4180672388095326e-02_wp, -1.2232505839045147e+00_wp, &
        zero, zero, gam, 5.4526025533510214e-01_wp, &
        zero, zero, zero, gam], [ns, ns])
    real(wp), parameter :: b_tab(ns) = [2.4212380706095346e-01_wp, -1.2232505839045147e+00_wp, &
                                        1.5452602553351020e+00_wp, gam]
    real(wp), parameter :: bhat_tab(ns) = [3.7810903145819369e-01_wp, -9.6042292212423178e-02_wp, &
                                           5.0000000000000000e-01_wp, 2.1793326075422950e-01_wp]
    real(wp), parameter :: bint_tab(ns, 3) = reshape([ &
        1.0564298455794094_wp, 2.296429974281067_wp, -1.307599564525376_wp, -1.045260255335102_wp, &
        -1.3864882699759573_wp, -8.262611700275677_wp, 7.250979895056055_wp, 2.398120075195581_wp, &
        0.5721822314575016_wp, 4.742931142090097_wp, -4.398120075195578_wp, -0.9169932983520199_wp], [ns, 3])
    !> Without a band (band = 1) a proposed step up to this factor longer
    !! than the last is not taken, so that the factorization of
    !! I - h gamma J can be reused.
    real(wp), parameter :: keep_step_factor = 1.2_wp

    !> The tableau in the transformed form of the implementation: stages
    !! u_i = sum_j gamma_ij k_j solve
    !!   (I - h gamma J) u_i = h gamma [ g(t + alpha_i h, y + sum_j a_ij u_j) + sum_j c_ij u_j / h ]
    !! with a = alpha Gamma^-1, c = diag(1/gamma) - Gamma^-1, y1 = y + sum m_i u_i.
    type :: rosw_tableau_t
        real(wp) :: a(ns, ns) = zero, c(ns, ns) = zero, m(ns) = zero, e(ns) = zero, alpha(ns) = zero
        real(wp) :: gi(ns, ns) = zero   !! Gamma^-1
    end type rosw_tableau_t

contains

    ! ------------------------------------------------------------------ ROS2

    !> The Jacobian is kept over a restart: at a kink of the inputs it changes little.
    module procedure ros2_reset_history
        if (.not. allocated(me%tdot)) then
            allocate (me%tdot(size(me%y)))
            me%jac_age = -1
        end if
        if (me%hnext <= zero) me%hnext = me%h
    end procedure ros2_reset_history

    !> Jacobian (forward differences of the whole system) and time
    !! derivative of g at the current point.
    subroutine ros2_jacobian(me, sys, stat, errmsg)
        class(ros2_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp), parameter :: dt_floor = 1.0e-3_wp   !! smallest time scale of the t difference [s]
        real(wp) :: dt, ft(size(me%y))
        call me%w%form_jacobian(sys, me%t, me%y, me%f, stat, errmsg, force_differences=.true.)
        if (stat /= stat_ok) return
        dt = sqrt(epsilon(one))*max(abs(me%t), dt_floor)
        call sys%rhs(me%t + dt, me%y, ft, stat, errmsg)
        if (stat /= stat_ok) return
        me%tdot = (ft - me%f)/dt
        me%jac_age = 0
        me%njac = me%w%jacobians()
    end subroutine ros2_jacobian

    !> One step of the L-stable Rosenbrock pair of Shampine & Reichelt
    !! (MATLAB's ode23s): d = 1/(2 + sqrt 2), W = I - h d J,
    !!   k1 = W^-1 (F0 + h d T), F1 = g(t + h/2, y + h k1/2)
    !!   k2 = W^-1 (F1 - k1) + k1, ynew = y + h k2, F2 = g(t + h, ynew)
    !!   k3 = W^-1 (F2 - e32 (k2 - F1) - 2 (k1 - F0) + h d T)
    !!   error = h (k1 - 2 k2 + k3) / 6
    !! with T = dg/dt by a forward difference.
    module procedure ros2_step
        real(wp), parameter :: d = one/(two + sqrt(two)), e32 = 6.0_wp + sqrt(two)
        real(wp), dimension(size(me%y)) :: k1, k2, k3, f1, f2, ynew
        real(wp) :: h, err
        stat = stat_ok; errmsg = ''
        if (me%jac_age < 0 .or. me%jac_age >= me%jac_age_max) then
            call ros2_jacobian(me, sys, stat, errmsg)
            if (stat /= stat_ok) return
        end if
        do
            h = clip_step(me%t, min(me%hnext, me%hmax), tstop)
            if (.not. me%w%factored_for(h*d)) then
                call me%w%factor(h*d, stat, errmsg)
                me%nfact = me%w%factorizations()
                if (stat /= stat_ok) then
                    write (errmsg, '(a,es12.5,a)') 'ROS2: '//trim(errmsg)//' at t = ', me%t, ' s'
                    return
                end if
            end if
            k1 = me%f + h*d*me%tdot
            call me%w%solve(k1)
            call sys%rhs(me%t + half*h, me%y + half*h*k1, f1, stat, errmsg)
            if (stat /= stat_ok) return
            k2 = f1 - k1
            call me%w%solve(k2)
            k2 = k2 + k1
            ynew = me%y + h*k2
            call sys%rhs(me%t + h, ynew, f2, stat, errmsg)
            if (stat /= stat_ok) return
            k3 = f2 - e32*(k2 - f1) - two*(k1 - me%f) + h*d*me%tdot
            call me%w%solve(k3)
            err = max(err_norm(me, h/6.0_wp*(k1 - two*k2 + k3), me%y, ynew), err_floor)
            if (err <= one) exit
            call shrink_after_rejection(me, h, err, 0.8_wp, me%hnext, stat, errmsg)
            if (stat /= stat_ok) return
            ! an aged Jacobian may be the cause: form a fresh one
            if (me%jac_age > 0) call ros2_jacobian(me, sys, stat, errmsg)
            if (stat /= stat_ok) return
        end do
        me%jac_age = me%jac_age + 1
        if (h >= me%hnext*unclipped .or. err > half) me%hnext = h*min(fac_max, max(fac_min, 0.8_wp*err**(-one/3.0_wp)))
        call accept(me, me%t + h, ynew, f2)
    end procedure ros2_step

    !> A rejected step of an order-2(3) pair: count it and shrink the step by
    !! safety err^(-1/3) (at most to fac_min); stat_step_failed below hmin.
    subroutine shrink_after_rejection(me, h, err, safety, hnext, stat, errmsg)
        class(integrator_t), intent(inout) :: me
        real(wp), intent(in) :: h, err, safety
        real(wp), intent(out) :: hnext
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        stat = stat_ok
        errmsg = ''
        me%nreject = me%nreject + 1
        hnext = h*max(fac_min, safety*err**(-one/3.0_wp))
        if (hnext < me%hmin) call step_too_small(me%t, me%hmin, stat, errmsg)
    end subroutine shrink_after_rejection

    ! ------------------------------------------------------------------ ROS34PW2

    !> The transformed tableau of ROS34PW2 (a, c, m, error weights, the
    !! stage times alpha_i and Gamma^-1 for the dense output).
    pure function rosw_tableau() result(tb)
        type(rosw_tableau_t) :: tb
        integer :: i, j, k
        ! inverse of the lower triangular Gamma, column by column
        do j = 1, ns
            tb%gi(j, j) = one/gamma_tab(j, j)
            do i = j + 1, ns
                tb%gi(i, j) = -sum([(gamma_tab(i, k)*tb%gi(k, j), k=j, i - 1)])/gamma_tab(i, i)
            end do
        end do
        tb%a = matmul(alpha_tab, tb%gi)
        tb%c = -tb%gi
        do i = 1, ns
            tb%c(i, i) = zero
            tb%alpha(i) = sum(alpha_tab(i, :))
        end do
        tb%m = matmul(b_tab, tb%gi)
        tb%e = matmul(b_tab - bhat_tab, tb%gi)
    end function rosw_tableau

    !> A restart keeps the Jacobian (it changes little at a kink of the inputs).
    module procedure rosw_reset_history
        if (.not. allocated(me%u)) then
            allocate (me%u(size(me%y), ns))
            me%jac_age = -1
        end if
        me%u = zero
        if (me%hnext <= zero) me%hnext = me%h
    end procedure rosw_reset_history

    !> Form the Jacobian at the current point.
    subroutine rosw_jacobian(me, sys, stat, errmsg)
        class(rosw_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        call me%w%form_jacobian(sys, me%t, me%y, me%f, stat, errmsg)
        me%jac_age = 0
        me%njac = me%w%jacobians()
    end subroutine rosw_jacobian

    !> One accepted ROS34PW2 step: four stages with one factorization of
    !! I - h gamma J (reused while J stays and h is in its band), error from the embedded
    !! order-2 solution, the next step from err^(-1/3).
    module procedure rosw_step
        type(rosw_tableau_t) :: tb
        real(wp), dimension(size(me%y)) :: ynew, fnew
        real(wp) :: h, err, fac
        logical :: rejected
        stat = stat_ok; errmsg = ''
        rejected = .false.
        tb = rosw_tableau()
        if (me%jac_age < 0 .or. me%jac_age >= me%jac_steps) then
            call rosw_jacobian(me, sys, stat, errmsg)
            if (stat /= stat_ok) return
        end if
        do
            h = clip_step(me%t, min(me%hnext, me%hmax), tstop)
            call rosw_stages(me, sys, tb, h, ynew, err, stat, errmsg)
            if (stat /= stat_ok) return
            if (err <= one) exit
            rejected = .true.
            call shrink_after_rejection(me, h, err, 0.9_wp, me%hnext, stat, errmsg)
            if (stat /= stat_ok) return
            ! an aged Jacobian may be the cause: form a fresh one
            if (me%jac_age > 0) call rosw_jacobian(me, sys, stat, errmsg)
            if (stat /= stat_ok) return
        end do
        call sys%rhs(me%t + h, ynew, fnew, stat, errmsg)
        if (stat /= stat_ok) return
        me%jac_age = me%jac_age + 1
        fac = 0.9_wp*err**(-one/3.0_wp)
        ! Gustafsson's predictive controller (as in RADAU5 and RODAS): the
        ! smaller of the standard step and the one predicted from the error
        ! ratio of the last two accepted steps
        if (me%hacc > zero) fac = min(fac, 0.9_wp*(h/me%hacc)*(me%erracc/err**2)**(one/3.0_wp))
        me%hacc = h
        me%erracc = max(1.0e-2_wp, err)
        fac = min(fac_max, max(fac_min, fac))
        ! no growth right after a rejection (Hairer & Wanner's safeguard)
        if (rejected) fac = min(fac, one)
        ! a clipped step does not shrink the next; without a band a small
        ! increase is not worth a new factorization
        if (h >= me%hnext*unclipped .or. fac < one) then
            me%hnext = h*fac
            if (me%band <= one .and. fac >= one .and. fac <= keep_step_factor) me%hnext = h
        end if
        call accept(me, me%t + h, ynew, fnew)
    end procedure rosw_step

    !> The four stages of one attempt with step h: ynew and the error norm.
    subroutine rosw_stages(me, sys, tb, h, ynew, err, stat, errmsg)
        class(rosw_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        type(rosw_tableau_t), intent(in) :: tb
        real(wp), intent(in) :: h
        real(wp), intent(out) :: ynew(:), err
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp) :: hg, ys(size(ynew)), fs(size(ynew)), r(size(ynew))
        integer :: i, j
        hg = h*gam
        ! with the factorization of another step h0 in the band, the stages
        ! solve with the Jacobian (h0/h) J: a W-method keeps its classical
        ! order (on stiff components an inexact Jacobian costs accuracy)
        if (.not. me%w%factored_for(hg, me%band)) then
            call me%w%factor(hg, stat, errmsg)
            me%nfact = me%w%factorizations()
            if (stat /= stat_ok) then
                write (errmsg, '(a,es12.5,a)') 'ROS34PW2: '//trim(errmsg)//' at t = ', me%t, ' s'
                return
            end if
        end if
        do i = 1, ns
            if (i == 1) then
                fs = me%f
            else
                ys = me%y
                do j = 1, i - 1
                    ys = ys + tb%a(i, j)*me%u(:, j)
                end do
                call sys%rhs(me%t + tb%alpha(i)*h, ys, fs, stat, errmsg)
                if (stat /= stat_ok) return
            end if
            r = fs
            do j = 1, i - 1
                r = r + (tb%c(i, j)/h)*me%u(:, j)
            end do
            r = hg*r
            call me%w%solve(r)
            me%u(:, i) = r
        end do
        ynew = me%y
        r = zero
        do i = 1, ns
            ynew = ynew + tb%m(i)*me%u(:, i)
            r = r + tb%e(i)*me%u(:, i)
        end do
        err = max(err_norm(me, r, me%y, ynew), err_floor)
        stat = stat_ok
    end subroutine rosw_stages

    !> Dense output of order 3 from the stages of the last step (the
    !! interpolant of Rang & Angermann's method as tabulated by PETSc's
    !! TSROSW), and its derivative.
    module procedure rosw_interpolate
        type(rosw_tableau_t) :: tb
        real(wp) :: h, s, bth(ns), dbth(ns), dj, ddj
        integer :: i, j
        if (at_current_point(me, tout, yout, dydt)) return
        h = me%t - me%told
        tb = rosw_tableau()
        s = (tout - me%told)/h
        do i = 1, ns
            bth(i) = s*(bint_tab(i, 1) + s*(bint_tab(i, 2) + s*bint_tab(i, 3)))
            dbth(i) = bint_tab(i, 1) + s*(two*bint_tab(i, 2) + 3.0_wp*s*bint_tab(i, 3))
        end do
        yout = me%yold
        if (present(dydt)) dydt = zero
        do j = 1, ns
            dj = dot_product(bth, tb%gi(:, j))
            yout = yout + dj*me%u(:, j)
            if (present(dydt)) then
                ddj = dot_product(dbth, tb%gi(:, j))
                dydt = dydt + (ddj/h)*me%u(:, j)
            end if
        end do
    end procedure rosw_interpolate

end submodule hn_integrators_rosenbrock
