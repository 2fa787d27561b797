!> Injury criteria from sampled time histories:
!!  HIC (49 CFR 571.208 S6.2): max over t1 < t2, t2 - t1 <= window (15 or
!!      36 ms) of (t2 - t1) [ int_t1^t2 a dt / (t2 - t1) ]^2.5, a the
!!      resultant head acceleration in g, t in s;
!!  Nij (S6.6): Fz/Fzc + My/Myc at the occipital condyle in each of the four
!!      modes tension-extension, tension-flexion, compression-extension,
!!      compression-flexion (Hybrid III 50th intercepts by default; the
!!      other occupants' sets in `occupants`);
!!  NIC (Bostrom et al. 1996, a rear-impact criterion): 0.2 a_rel + v_rel^2,
!!      a_rel = a_x,T1 - a_x,head [m/s^2], v_rel = int a_rel dt.
!! Filtering (CFC 1000 for HIC, 600 for Nij, 60 for NIC) is the caller's.
!!
!! The values compared with are injury assessment reference values of
!! crash-test dummies in a regulation, not limits of this human model.
module hn_injury
    use hn_kinds, only: wp, zero
    implicit none
    private

    public :: hic, nij, nic, nij_intercepts_t, occupant_t, occupants, occupant_index, mode_sums

    !> Critical intercepts of Nij [N, N m]; defaults: Hybrid III 50th male.
    type :: nij_intercepts_t
        real(wp) :: fz_tension = 6806.0_wp
        real(wp) :: fz_compression = 6160.0_wp
        real(wp) :: my_flexion = 310.0_wp
        real(wp) :: my_extension = 135.0_wp
    end type nij_intercepts_t

    !> An occupant size of 49 CFR 571.208 (FMVSS 208): its Nij intercepts and
    !! the reference values of peak upper-neck tension and compression.
    type :: occupant_t
        character(len=4) :: code = ''              !! CRITERIA card name
        character(len=40) :: label = ''            !! the dummy, for listings
        type(nij_intercepts_t) :: crit             !! Nij intercepts (in position)
        real(wp) :: tension = zero                 !! peak tension reference value [N]
        real(wp) :: compression = zero             !! peak compression reference value [N], positive
        character(len=60) :: source = ''           !! where the values are set
        logical :: verified = .false.              !! values checked against the regulation text
    end type occupant_t

    !> The occupants selectable on the CRITERIA card; the first is the default.
    !! Nij intercepts (in position), 49 CFR 571.208: H50M S6.6 (Fzc 6806 N
    !! tension, 6160 N compression; Myc 310 N m flexion, 135 N m extension;
    !! as in reference-data.md); H05F S15.3.6 (4287 N, 3880 N; 155 N m,
    !! 67 N m), the same values as the open-source pyisomme
    !! (calculate/neck_nij.py, in-position Hybrid III 5th female). The H05F
    !! peak tension and compression were not checked (`verified` false).
    !! The 95th male, 6- and 3-year-old and CRABI sets entered earlier were
    !! removed: no source for them could be checked.
    type(occupant_t), parameter :: occupants(2) = [ &
        occupant_t('H50M', 'HYBRID III 50TH MALE', nij_intercepts_t(6806.0_wp, 6160.0_wp, 310.0_wp, 135.0_wp), &
                   4170.0_wp, 4000.0_wp, '49 CFR 571.208 S6.6', .true.), &
        occupant_t('H05F', 'HYBRID III 5TH FEMALE', nij_intercepts_t(4287.0_wp, 3880.0_wp, 155.0_wp, 67.0_wp), &
                   2620.0_wp, 2520.0_wp, '49 CFR 571.208 S15.3.6', .false.)]

contains

    !> Index in `occupants` of the occupant called `code`, 0 when none is.
    pure integer function occupant_index(code) result(k)
        character(len=*), intent(in) :: code   !! an occupant code (H50M, H05F, ...)
        k = findloc(occupants%code, code, dim=1)
    end function occupant_index

    !> HIC over windows up to `window` seconds of the resultant acceleration
    !! a [g] sampled every dt [s]; t1, t2 are the sample times (from 0) of
    !! the maximizing interval.
    pure subroutine hic(a, dt, window, value, t1, t2)
        real(wp), intent(in) :: a(:)     !! resultant head acceleration [g], CFC 1000
        real(wp), intent(in) :: dt       !! sample interval [s]
        real(wp), intent(in) :: window   !! longest interval t2 - t1 [s] (0.015 or 0.036)
        real(wp), intent(out) :: value   !! HIC (0 when no interval has a positive mean)
        real(wp), intent(out) :: t1      !! start of the maximizing interval [s from the first sample]
        real(wp), intent(out) :: t2      !! its end [s from the first sample]
        real(wp) :: c(size(a)), avg, h, span
        integer :: i, j, n, w
        n = size(a)
        value = zero; t1 = zero; t2 = zero
        if (n < 2) return
        c(1) = zero
        do i = 2, n
            c(i) = c(i - 1) + 0.5_wp*(a(i) + a(i - 1))*dt
        end do
        w = int(window/dt + 1.0e-9_wp)
        do i = 1, n - 1
            do j = i + 1, min(n, i + w)
                span = (j - i)*dt
                avg = (c(j) - c(i))/span
                if (avg <= zero) cycle
                h = span*avg*avg*sqrt(avg)          ! avg**2.5 without a call of pow
                if (h > value) then
                    value = h; t1 = (i - 1)*dt; t2 = (j - 1)*dt
                end if
            end do
        end do
    end subroutine hic

    !> The four Nij modes at every sample, zero where a mode does not apply:
    !! fz > 0 tension, my > 0 flexion (loads of the head on the neck at the OC).
    pure subroutine nij(fz, my, crit, nte, ntf, nce, ncf)
        real(wp), intent(in) :: fz(:)                       !! axial force at the OC, tension positive [N]
        real(wp), intent(in) :: my(:)                       !! moment at the OC, flexion positive [N m]
        type(nij_intercepts_t), intent(in) :: crit          !! critical intercepts Fzc, Myc
        real(wp), intent(out), dimension(size(fz)) :: nte   !! tension-extension Nij
        real(wp), intent(out), dimension(size(fz)) :: ntf   !! tension-flexion Nij
        real(wp), intent(out), dimension(size(fz)) :: nce   !! compression-extension Nij
        real(wp), intent(out), dimension(size(fz)) :: ncf   !! compression-flexion Nij
        call mode_sums(fz, my, crit%fz_tension, crit%fz_compression, crit%my_flexion, crit%my_extension, &
                       ntf, nte, ncf, nce)
    end subroutine nij

    !> The four normalized sums |x|/cx + |y|/cy of two signed loads, each in
    !! its quadrant of (x, y) and zero outside it: x >= 0 or x < 0, y >= 0 or
    !! y <= 0 (Nij's modes, hn_whiplash's Nkm).
    pure subroutine mode_sums(x, y, cx_pos, cx_neg, cy_pos, cy_neg, pp, pn, np, nn)
        real(wp), intent(in) :: x(:)                       !! first load
        real(wp), intent(in) :: y(:)                       !! second load
        real(wp), intent(in) :: cx_pos                     !! intercept of x >= 0 (positive)
        real(wp), intent(in) :: cx_neg                     !! intercept of x < 0 (positive)
        real(wp), intent(in) :: cy_pos                     !! intercept of y >= 0 (positive)
        real(wp), intent(in) :: cy_neg                     !! intercept of y <= 0 (positive)
        real(wp), intent(out), dimension(size(x)) :: pp    !! x >= 0, y >= 0
        real(wp), intent(out), dimension(size(x)) :: pn    !! x >= 0, y <= 0
        real(wp), intent(out), dimension(size(x)) :: np    !! x < 0, y >= 0
        real(wp), intent(out), dimension(size(x)) :: nn    !! x < 0, y <= 0
        real(wp) :: xp, xn, yp, yn
        integer :: i
        do i = 1, size(x)
            xp = max(x(i), zero)/cx_pos
            xn = max(-x(i), zero)/cx_neg
            yp = max(y(i), zero)/cy_pos
            yn = max(-y(i), zero)/cy_neg
            pp(i) = merge(xp + yp, zero, x(i) >= zero .and. y(i) >= zero)
            pn(i) = merge(xp + yn, zero, x(i) >= zero .and. y(i) <= zero)
            np(i) = merge(xn + yp, zero, x(i) < zero .and. y(i) >= zero)
            nn(i) = merge(xn + yn, zero, x(i) < zero .and. y(i) <= zero)
        end do
    end subroutine mode_sums

    !> NIC(t) = 0.2 a_rel + v_rel^2 from the x-accelerations of T1 and the
    !! head [m/s^2], v_rel the trapezoidal integral of a_rel from the first sample.
    pure subroutine nic(ax_t1, ax_head, dt, value)
        real(wp), intent(in) :: ax_t1(:)              !! x-acceleration of T1 [m/s^2], CFC 60
        real(wp), intent(in) :: ax_head(:)            !! x-acceleration of the head [m/s^2], CFC 60
        real(wp), intent(in) :: dt                    !! sample interval [s]
        real(wp), intent(out) :: value(size(ax_t1))   !! NIC at every sample [m^2/s^2]
        real(wp) :: arel(size(ax_t1)), v
        integer :: i
        arel = ax_t1 - ax_head
        v = zero
        do i = 1, size(arel)
            if (i > 1) v = v + 0.5_wp*(arel(i) + arel(i - 1))*dt
            value(i) = 0.2_wp*arel(i) + v**2
        end do
    end subroutine nic

end module hn_injury
