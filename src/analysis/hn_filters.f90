!> SAE J211/1 Appendix C channel-class filters (CFC 60, 180, 600, 1000):
!! a two-pole Butterworth-type recursion run forward and then backward, so
!! the result has zero phase and four-pole attenuation.
!!   wd = 2 pi CFC 2.0775,  wa = tan(wd T / 2)
!!   a0 = wa^2 / (1 + sqrt(2) wa + wa^2), a1 = 2 a0, a2 = a0
!!   b1 = -2 (wa^2 - 1) / (1 + sqrt(2) wa + wa^2)
!!   b2 = (-1 + sqrt(2) wa - wa^2) / (1 + sqrt(2) wa + wa^2)
!!   y(n) = a0 x(n) + a1 x(n-1) + a2 x(n-2) + b1 y(n-1) + b2 y(n-2)
!! Each pass starts from rest at the first sample of its direction (the
!! history is filled with that sample), which avoids a start-up transient.
module hn_filters
    use hn_kinds, only: wp, pi, one, two
    implicit none
    private

    public :: cfc_filter, cfc_coefficients

contains

    !> Coefficients a0, a1, a2, b1, b2 for class `cfc` [Hz] at sample interval dt [s].
    pure subroutine cfc_coefficients(cfc, dt, a, b)
        real(wp), intent(in) :: cfc       !! channel frequency class [Hz]
        real(wp), intent(in) :: dt        !! sample interval [s]
        real(wp), intent(out) :: a(0:2)   !! a0, a1, a2 (input weights)
        real(wp), intent(out) :: b(1:2)   !! b1, b2 (output feedback weights)
        real(wp) :: wd, wa, den
        wd = two*pi*cfc*2.0775_wp
        wa = tan(wd*dt/two)
        den = one + sqrt(two)*wa + wa**2
        a(0) = wa**2/den
        a(1) = two*a(0)
        a(2) = a(0)
        b(1) = -two*(wa**2 - one)/den
        b(2) = (-one + sqrt(two)*wa - wa**2)/den
    end subroutine cfc_coefficients

    !> Zero-phase CFC filtering of x sampled at dt into y.
    pure subroutine cfc_filter(x, dt, cfc, y)
        real(wp), intent(in) :: x(:)   !! samples
        real(wp), intent(in) :: dt     !! sample interval [s]
        real(wp), intent(in) :: cfc    !! channel frequency class: 60, 180, 600 or 1000 [Hz]
        real(wp), intent(out) :: y(:)  !! filtered samples
        real(wp) :: a(0:2), b(1:2), tmp(size(x))
        call cfc_coefficients(cfc, dt, a, b)
        call one_pass(x, tmp)
        call one_pass(tmp(size(x):1:-1), y)
        y = y(size(x):1:-1)
    contains
        pure subroutine one_pass(u, v)
            real(wp), intent(in) :: u(:)
            real(wp), intent(out) :: v(:)
            real(wp) :: u1, u2, v1, v2
            integer :: n
            u1 = u(1); u2 = u(1); v1 = u(1); v2 = u(1)
            do n = 1, size(u)
                v(n) = a(0)*u(n) + a(1)*u1 + a(2)*u2 + b(1)*v1 + b(2)*v2
                u2 = u1; u1 = u(n)
                v2 = v1; v1 = v(n)
            end do
        end subroutine one_pass
    end subroutine cfc_filter

end module hn_filters
