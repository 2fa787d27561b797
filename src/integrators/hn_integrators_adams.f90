!> The variable-order Adams PECE method of Shampine & Gordon (1975) in the
!! modified divided-difference form, with local error control in the
!! weighted RMS norm and order selection 1-12; one step is split into the
!! blocks of the original: coefficients, predict and estimate, retreat
!! after a failure, correct, and the choice of the next order and step.
submodule(hn_integrators) hn_integrators_adams
    implicit none

    !> |gamma*| error constants of the Adams-Moulton formulas (Shampine & Gordon).
    real(wp), parameter :: gstr(13) = [0.500_wp, 0.0833_wp, 0.0417_wp, 0.0264_wp, 0.0188_wp, 0.0143_wp, &
                                       0.0114_wp, 0.00936_wp, 0.00789_wp, 0.00679_wp, 0.00592_wp, &
                                       0.00524_wp, 0.00468_wp]
    real(wp), parameter :: two_pow(13) = [2.0_wp, 4.0_wp, 8.0_wp, 16.0_wp, 32.0_wp, 64.0_wp, 128.0_wp, &
                                          256.0_wp, 512.0_wp, 1024.0_wp, 2048.0_wp, 4096.0_wp, 8192.0_wp]
    !> Errors are measured against the weights wt: the step passes at err <= eps.
    real(wp), parameter :: eps = one
    integer, parameter :: max_order = 12

    !> Error estimates of one attempt at orders k-2, k-1, k and the test error.
    type :: adams_errors_t
        real(wp) :: erkm2 = zero, erkm1 = zero, erk = zero, err = zero
        integer :: knew = 1
    end type adams_errors_t

contains

    !> A restart empties the differences; the next step starts at order 1.
    module procedure adams_reset_history
        integer :: n
        n = size(me%y)
        if (.not. allocated(me%phi)) allocate (me%phi(n, 16), me%wt(n))
        me%start = .true.
        me%phi = zero
    end procedure adams_reset_history

    !> One step of the variable-order Adams PECE method.
    module procedure adams_step
        real(wp), dimension(size(me%y)) :: p, yp
        type(adams_errors_t) :: e
        real(wp) :: hwant
        stat = stat_ok; errmsg = ''
        me%wt = me%atol + me%rtol*abs(me%y)
        if (me%start) call adams_first_step(me)
        hwant = me%hs
        ! land on tstop: a step that would pass it is shortened (the formula
        ! coefficients follow any step size, so nothing else changes)
        if (me%t + stretch*me%hs >= tstop) me%hs = tstop - me%t
        do
            call adams_coefficients(me)
            call adams_predict(me, sys, p, yp, e, stat, errmsg)
            if (stat /= stat_ok) return
            if (e%err <= eps) exit
            call adams_retreat(me, e)
            if (me%hs < me%hmin) then
                call step_too_small(me%t, me%hmin, stat, errmsg)
                return
            end if
        end do
        call adams_correct(me, sys, p, yp, stat, errmsg)
        if (stat /= stat_ok) return
        call adams_next_order_and_step(me, e, hwant)
    end procedure adams_step

    !> The first step after a start or restart: order 1 and a step size from
    !! the size of f.
    subroutine adams_first_step(me)
        class(adams_t), intent(inout) :: me
        real(wp) :: temp1, absh
        integer :: n
        n = size(me%y)
        me%phi(:, 1) = me%f
        me%phi(:, 2) = zero
        temp1 = sqrt(sum((me%f/me%wt)**2)/n)
        absh = min(me%h, me%hmax)
        if (eps < 16.0_wp*temp1*absh**2) absh = 0.25_wp*sqrt(eps/temp1)
        me%hs = max(absh, me%hmin)
        me%hold = zero; me%k = 1; me%kold = 0; me%start = .false.; me%phase1 = .true.
        me%ns = 0; me%ifail = 0
        me%g(1) = one; me%g(2) = half; me%sig(1) = one
    end subroutine adams_first_step

    !> Block 1: the coefficients of the formulas for this step.
    subroutine adams_coefficients(me)
        class(adams_t), intent(inout) :: me
        real(wp) :: temp1, temp2, temp5, temp6, reali
        integer :: i, iq, j, kp1, kp2, nsp1, nsp2, limit1, limit2, im1
        kp1 = me%k + 1; kp2 = me%k + 2
        if (me%hs /= me%hold) me%ns = 0
        if (me%ns <= me%kold) me%ns = me%ns + 1
        nsp1 = me%ns + 1
        if (me%k < me%ns) return
        me%beta(me%ns) = one
        me%alpha(me%ns) = one/me%ns
        temp1 = me%hs*me%ns
        me%sig(nsp1) = one
        if (me%k >= nsp1) then
            do i = nsp1, me%k
                im1 = i - 1
                temp2 = me%psi(im1)
                me%psi(im1) = temp1
                me%beta(i) = me%beta(im1)*me%psi(im1)/temp2
                temp1 = temp2 + me%hs
                me%alpha(i) = me%hs/temp1
                reali = i
                me%sig(i + 1) = reali*me%alpha(i)*me%sig(i)
            end do
        end if
        me%psi(me%k) = temp1
        if (me%ns <= 1) then
            do iq = 1, me%k
                me%v(iq) = one/(iq*(iq + 1))
                me%w(iq) = me%v(iq)
            end do
        else
            if (me%k > me%kold) then
                me%v(me%k) = one/(me%k*kp1)
                do j = 1, me%ns - 2
                    i = me%k - j
                    me%v(i) = me%v(i) - me%alpha(j + 1)*me%v(i + 1)
                end do
            end if
            limit1 = kp1 - me%ns
            temp5 = me%alpha(me%ns)
            do iq = 1, limit1
                me%v(iq) = me%v(iq) - temp5*me%v(iq + 1)
                me%w(iq) = me%v(iq)
            end do
            me%g(nsp1) = me%w(1)
        end if
        nsp2 = me%ns + 2
        if (kp1 >= nsp2) then
            do i = nsp2, kp1
                limit2 = kp2 - i
                temp6 = me%alpha(i - 1)
                do iq = 1, limit2
                    me%w(iq) = me%w(iq) - temp6*me%w(iq + 1)
                end do
                me%g(i) = me%w(1)
            end do
        end if
    end subroutine adams_coefficients

    !> Block 2: predict p, evaluate yp = g(t + hs, p), estimate the local
    !! error at orders k, k-1, k-2 and propose the order knew.
    subroutine adams_predict(me, sys, p, yp, e, stat, errmsg)
        class(adams_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(out) :: p(:), yp(:)
        type(adams_errors_t), intent(out) :: e
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp) :: absh, temp3, temp4, temp5
        integer :: i, j, l, n, kp1, kp2, km1, km2, nsp1
        n = size(me%y)
        kp1 = me%k + 1; kp2 = me%k + 2; km1 = me%k - 1; km2 = me%k - 2
        nsp1 = me%ns + 1
        if (me%k >= nsp1) then
            do i = nsp1, me%k
                me%phi(:, i) = me%beta(i)*me%phi(:, i)
            end do
        end if
        me%phi(:, kp2) = me%phi(:, kp1)
        me%phi(:, kp1) = zero
        p = zero
        do j = 1, me%k
            i = kp1 - j
            p = p + me%g(i)*me%phi(:, i)
            me%phi(:, i) = me%phi(:, i) + me%phi(:, i + 1)
        end do
        p = me%y + me%hs*p
        call sys%rhs(me%t + me%hs, p, yp, stat, errmsg)
        if (stat /= stat_ok) return
        absh = abs(me%hs)
        do l = 1, n
            temp3 = one/me%wt(l)
            temp4 = yp(l) - me%phi(l, 1)
            if (km2 > 0) e%erkm2 = e%erkm2 + ((me%phi(l, km1) + temp4)*temp3)**2
            if (km2 >= 0) e%erkm1 = e%erkm1 + ((me%phi(l, me%k) + temp4)*temp3)**2
            e%erk = e%erk + (temp4*temp3)**2
        end do
        e%erkm2 = sqrt(e%erkm2/n); e%erkm1 = sqrt(e%erkm1/n); e%erk = sqrt(e%erk/n)
        if (km2 > 0) e%erkm2 = absh*me%sig(km1)*gstr(km2)*e%erkm2
        if (km2 >= 0) e%erkm1 = absh*me%sig(me%k)*gstr(km1)*e%erkm1
        temp5 = absh*e%erk
        e%err = temp5*(me%g(me%k) - me%g(kp1))
        e%erk = temp5*me%sig(kp1)*gstr(me%k)
        e%knew = me%k
        if (km2 > 0) then
            if (max(e%erkm1, e%erkm2) <= e%erk) e%knew = km1
        else if (km2 == 0) then
            if (e%erkm1 <= half*e%erk) e%knew = km1
        end if
    end subroutine adams_predict

    !> Block 3: the step failed; restore the differences and retry with a
    !! smaller step (order 1 after three failures).
    subroutine adams_retreat(me, e)
        class(adams_t), intent(inout) :: me
        type(adams_errors_t), intent(in) :: e
        real(wp) :: temp1, temp2
        integer :: i, knew
        knew = e%knew
        me%phase1 = .false.
        me%nreject = me%nreject + 1
        do i = 1, me%k
            temp1 = one/me%beta(i)
            me%phi(:, i) = temp1*(me%phi(:, i) - me%phi(:, i + 1))
        end do
        do i = 2, me%k
            me%psi(i - 1) = me%psi(i) - me%hs
        end do
        me%ifail = me%ifail + 1
        temp2 = half
        if (me%ifail > 3 .and. half*eps < 0.25_wp*e%erk) temp2 = sqrt(half*eps/e%erk)
        if (me%ifail >= 3) knew = 1
        me%hs = temp2*me%hs
        me%k = knew
    end subroutine adams_retreat

    !> Block 4: the step succeeded; correct, evaluate, update the differences.
    subroutine adams_correct(me, sys, p, yp, stat, errmsg)
        class(adams_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: p(:)
        real(wp), intent(inout) :: yp(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp) :: ynew(size(p)), temp1
        integer :: i, kp1, kp2
        kp1 = me%k + 1; kp2 = me%k + 2
        me%kold = me%k
        me%hold = me%hs
        temp1 = me%hs*me%g(kp1)
        ynew = p + temp1*(yp - me%phi(:, 1))
        call sys%rhs(me%t + me%hs, ynew, yp, stat, errmsg)
        if (stat /= stat_ok) return
        me%phi(:, kp1) = yp - me%phi(:, 1)
        me%phi(:, kp2) = me%phi(:, kp1) - me%phi(:, kp2)
        do i = 1, me%k
            me%phi(:, i) = me%phi(:, i) + me%phi(:, kp1)
        end do
        call accept(me, me%t + me%hs, ynew, yp)
        me%ifail = 0
    end subroutine adams_correct

    !> The order and step size of the next step.
    subroutine adams_next_order_and_step(me, e, hwant)
        class(adams_t), intent(inout) :: me
        type(adams_errors_t), intent(in) :: e
        real(wp), intent(in) :: hwant    !! the step wanted before landing on tstop
        real(wp) :: erk, erkp1, absh, r, hnew
        integer :: n, kp1, kp2, km1
        n = size(me%y)
        kp1 = me%k + 1; kp2 = me%k + 2; km1 = me%k - 1
        absh = abs(me%hs)
        erk = e%erk
        erkp1 = zero
        if (e%knew == km1 .or. me%k == max_order) me%phase1 = .false.
        if (me%phase1) then
            me%k = kp1; erk = erkp1
        else if (e%knew == km1) then
            me%k = km1; erk = e%erkm1
        else if (kp1 <= me%ns) then
            erkp1 = absh*gstr(kp1)*sqrt(sum((me%phi(:, kp2)/me%wt)**2)/n)
            if (me%k > 1) then
                if (e%erkm1 <= min(erk, erkp1)) then
                    me%k = km1; erk = e%erkm1
                else if (erkp1 < erk .and. me%k /= max_order) then
                    me%k = kp1; erk = erkp1
                end if
            else if (erkp1 < half*erk) then
                me%k = kp1; erk = erkp1
            end if
        end if
        if (me%phase1 .or. half*eps >= erk*two_pow(me%k + 1)) then
            hnew = two*me%hs
        else if (half*eps >= erk) then
            hnew = me%hs
        else
            r = (half*eps/erk)**(one/(me%k + 1))
            hnew = absh*max(half, min(0.9_wp, r))
        end if
        ! a step shortened to land on tstop does not shrink the next one
        if (me%hs < hwant .and. hnew < hwant) hnew = min(hwant, two*me%hs)
        me%hs = min(max(hnew, me%hmin), me%hmax)
    end subroutine adams_next_order_and_step

    !> Shampine & Gordon's interpolation from the divided differences of the
    !! last step (order kold), with the derivative of the interpolant.
    module procedure adams_interpolate
        real(wp) :: hi, term, gamma, eta, psijm1, gi(13), wi(13), rho(13)
        integer :: i, j, ki, kip1, limit1
        if (at_current_point(me, tout, yout, dydt)) return
        hi = tout - me%t
        ki = me%kold + 1
        kip1 = ki + 1
        do i = 1, ki
            wi(i) = one/i
        end do
        term = zero
        gi(1) = one
        rho(1) = one
        do j = 2, ki
            psijm1 = me%psi(j - 1)
            gamma = (hi + term)/psijm1
            eta = hi/psijm1
            limit1 = kip1 - j
            do i = 1, limit1
                wi(i) = gamma*wi(i) - eta*wi(i + 1)
            end do
            gi(j) = wi(1)
            rho(j) = gamma*rho(j - 1)
            term = psijm1
        end do
        yout = zero
        do j = 1, ki
            i = kip1 - j
            yout = yout + gi(i)*me%phi(:, i)
        end do
        yout = me%y + hi*yout
        if (present(dydt)) then
            dydt = zero
            do j = 1, ki
                i = kip1 - j
                dydt = dydt + rho(i)*me%phi(:, i)
            end do
        end if
    end procedure adams_interpolate

end submodule hn_integrators_adams
