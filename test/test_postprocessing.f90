!> SAE J211/1 channel filters and the injury criteria against closed forms.
program test_postprocessing
    use hn_kinds, only: wp, pi, zero, one
    use hn_filters, only: cfc_filter
    use hn_injury, only: hic, nij, nic, nij_intercepts_t
    use hn_testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: suite
    real(wp), parameter :: dt = 1.0e-4_wp     ! 10 kHz sampling

    call test_3db_gain(60.0_wp, 100.0_wp)
    call test_3db_gain(180.0_wp, 300.0_wp)
    call test_3db_gain(600.0_wp, 1000.0_wp)
    call test_3db_gain(1000.0_wp, 1650.0_wp)
    call test_passband_gain()
    call test_step_response()
    call test_hic_half_sine_short()
    call test_hic_half_sine_long()
    call test_nij_modes()
    call test_nic_constant()
    call suite%finish()

contains

    !> Amplitude ratio of a long sine of frequency f after filtering, measured
    !! away from the ends [dB]; sampled at 30 times the class's 3 dB frequency
    !! (1.667 CFC), as J211 asks for a sampling rate well above it.
    real(wp) function gain_db(cfc, f) result(g)
        real(wp), intent(in) :: cfc, f
        integer, parameter :: n = 40000
        real(wp) :: x(n), y(n), ds
        integer :: i
        ds = one/(30*1.6667_wp*cfc)
        do i = 1, n
            x(i) = sin(2*pi*f*(i - 1)*ds)
        end do
        call cfc_filter(x, ds, cfc, y)
        g = 20*log10(maxval(abs(y(n/4:3*n/4)))/maxval(abs(x(n/4:3*n/4))))
    end function gain_db

    subroutine test_3db_gain(cfc, f3)
        real(wp), intent(in) :: cfc, f3
        character(len=60) :: name
        write (name, '(a,i0,a,i0,a)') 'CFC ', nint(cfc), ' gain at ', nint(f3), ' Hz is -3 dB'
        call suite%near(gain_db(cfc, f3), -3.0_wp, 0.2_wp, trim(name))
    end subroutine test_3db_gain

    !> In the pass band (CFC 60 at 60 Hz) the gain stays within J211's +0.5/-1 dB.
    subroutine test_passband_gain()
        real(wp) :: g
        g = gain_db(60.0_wp, 60.0_wp)
        call suite%check(g < 0.5_wp .and. g > -1.0_wp, 'CFC 60 gain at 60 Hz within +0.5 / -1 dB', fmt_real(g))
    end subroutine test_passband_gain

    !> Zero phase: the filtered unit step is 1/2 at the step, symmetric about
    !! it, and settles to 1.
    subroutine test_step_response()
        integer, parameter :: n = 4001, m = 2001
        real(wp) :: x(n), y(n), asym
        integer :: i
        x = zero
        x(m + 1:) = one
        call cfc_filter(x, dt, 60.0_wp, y)
        asym = zero
        do i = 1, 500
            asym = max(asym, abs((y(m + i) - 0.5_wp) + (y(m + 1 - i) - 0.5_wp)))
        end do
        call suite%check(abs(0.5_wp*(y(m) + y(m + 1)) - 0.5_wp) < 1.0e-3_wp .and. asym < 1.0e-3_wp .and. &
                         abs(y(n) - one) < 1.0e-6_wp .and. abs(y(1)) < 1.0e-6_wp .and. maxval(y) < 1.1_wp, &
                         'CFC 60 step response: zero phase (1/2 at the step, symmetric), settles to 1', &
                         'asymmetry '//fmt_real(asym)//', overshoot '//fmt_real(maxval(y) - one))
    end subroutine test_step_response

    !> Half sine A sin(pi t / T), T = 10 ms, A = 80 g: the best window is
    !! centred, of width 2 T u / pi with tan u = 5u/3 (u = 1.0515...), and
    !! HIC = w^-1.5 (2 A T / pi)^2.5 sin(u)^2.5.
    subroutine test_hic_half_sine_short()
        real(wp), parameter :: a0 = 80.0_wp, tp = 0.010_wp
        real(wp) :: a(301), v, t1, t2, u, w, expect
        integer :: i
        do i = 1, size(a)
            a(i) = a0*max(zero, sin(pi*(i - 1)*dt/tp))
            if ((i - 1)*dt > tp) a(i) = zero
        end do
        u = 1.0_wp
        do i = 1, 50       ! Newton on tan(u) - 5u/3
            u = u - (tan(u) - 5*u/3)/(one/cos(u)**2 - 5.0_wp/3)
        end do
        w = 2*tp*u/pi
        expect = w**(-1.5_wp)*(2*a0*tp/pi)**2.5_wp*sin(u)**2.5_wp
        call hic(a, dt, 0.015_wp, v, t1, t2)
        call suite%near(v, expect, 2.0e-3_wp*expect, 'HIC15 of a 10 ms, 80 g half sine = closed form')
    end subroutine test_hic_half_sine_short

    !> A 40 ms half sine: the unconstrained best window (26.8 ms) exceeds 15
    !! ms, so HIC15 takes the centred 15 ms window; HIC36 the 26.8 ms one.
    subroutine test_hic_half_sine_long()
        real(wp), parameter :: a0 = 50.0_wp, tp = 0.040_wp
        real(wp) :: a(801), v15, v36, t1, t2, u, e15, e36
        integer :: i
        do i = 1, size(a)
            a(i) = zero
            if ((i - 1)*dt <= tp) a(i) = a0*sin(pi*(i - 1)*dt/tp)
        end do
        u = pi*0.015_wp/(2*tp)
        e15 = 0.015_wp**(-1.5_wp)*(2*a0*tp/pi)**2.5_wp*sin(u)**2.5_wp
        u = 1.0515_wp
        do i = 1, 50
            u = u - (tan(u) - 5*u/3)/(one/cos(u)**2 - 5.0_wp/3)
        end do
        e36 = (2*tp*u/pi)**(-1.5_wp)*(2*a0*tp/pi)**2.5_wp*sin(u)**2.5_wp
        call hic(a, dt, 0.015_wp, v15, t1, t2)
        call hic(a, dt, 0.036_wp, v36, t1, t2)
        call suite%check(abs(v15 - e15) < 2.0e-3_wp*e15 .and. abs(v36 - e36) < 2.0e-3_wp*e36, &
                         'HIC15 and HIC36 of a 40 ms half sine = closed forms (window limit)', &
                         'HIC15 '//fmt_real(v15)//' vs '//fmt_real(e15)//', HIC36 '//fmt_real(v36)//' vs '//fmt_real(e36))
    end subroutine test_hic_half_sine_long

    !> Hand-worked: half the tension intercept with half the flexion
    !! intercept is NTF = 1; half the compression intercept with half the
    !! extension intercept is NCE = 1; the other modes are zero there.
    subroutine test_nij_modes()
        type(nij_intercepts_t) :: c
        real(wp) :: nte(2), ntf(2), nce(2), ncf(2)
        call nij([3403.0_wp, -3080.0_wp], [155.0_wp, -67.5_wp], c, nte, ntf, nce, ncf)
        call suite%check(abs(ntf(1) - one) < 1.0e-12_wp .and. abs(nce(2) - one) < 1.0e-12_wp .and. &
                         nte(1) == zero .and. ncf(1) == zero .and. nce(1) == zero .and. &
                         ntf(2) == zero .and. nte(2) == zero .and. ncf(2) == zero, &
                         'Nij: NTF = 1 at (Fzc/2 tension, Myc/2 flexion), NCE = 1 at (Fzc/2 compression, Myc/2 extension)')
    end subroutine test_nij_modes

    !> a_rel = 10 m/s^2 held: v_rel = 10 t, NIC = 2 + 100 t^2.
    subroutine test_nic_constant()
        real(wp) :: v(1001)
        integer :: i
        call nic([(10.0_wp, i=1, 1001)], [(zero, i=1, 1001)], dt, v)
        call suite%near(v(1001), 2.0_wp + 100*0.1_wp**2, 1.0e-10_wp, 'NIC with a constant relative acceleration')
    end subroutine test_nic_constant

    function fmt_real(x) result(s)
        real(wp), intent(in) :: x
        character(len=12) :: s
        write (s, '(es12.4)') x
    end function fmt_real

end program test_postprocessing
