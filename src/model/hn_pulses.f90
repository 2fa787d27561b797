!> Sled pulses by name (the PULSE card, docs/deck-format.md): the closed
!! forms of the half-sine, haversine, triangle, trapezoid and ramp pulses
!! and their piecewise-linear tables. Values are in the units of whatever
!! uses the table (an acceleration: its velocity change is in the same
!! units times seconds).
!!
!! The knots: triangle, trapezoid and ramp exactly (their corners); the
!! sine shapes at `sine_segments` equal intervals, the values then scaled
!! so that the table's velocity change (the integral of the linear
!! interpolant) equals the closed form exactly. A table cannot jump: the
!! ramp rises over `ramp_edge` of its duration after the onset and falls
!! over as long after its end, so that its velocity change is exactly
!! peak x duration. A pulse with an onset after time 0 starts its table
!! with a zero knot at time 0 (tables hold their end values outside).
module hn_pulses
    use hn_kinds, only: wp, zero, one, half, pi
    implicit none
    private

    public :: pulse_shapes, pulse_code, pulse_dv_factor, pulse_knots, table_dv
    public :: pulse_halfsine, pulse_haversine, pulse_triangle, pulse_trapezoid, pulse_ramp
    public :: sine_segments, ramp_edge

    integer, parameter :: pulse_halfsine = 1, pulse_haversine = 2, pulse_triangle = 3, pulse_trapezoid = 4, &
                          pulse_ramp = 5
    !> The shape names of the PULSE card, in the order of the codes above.
    character(len=9), parameter :: pulse_shapes(5) = [character(len=9) :: 'HALFSINE', 'HAVERSINE', 'TRIANGLE', &
                                                      'TRAPEZOID', 'RAMP']
    !> Intervals of a sine shape's table (its linear interpolant's velocity
    !! change is within 2.1E-5 of the closed form before the scaling).
    integer, parameter :: sine_segments = 200
    !> Rise and fall time of a ramp, as a fraction of its duration.
    real(wp), parameter :: ramp_edge = 1.0e-4_wp

contains

    !> The code of a shape name (0: not a shape).
    pure integer function pulse_code(name) result(code)
        character(len=*), intent(in) :: name   !! the shape name, upper case
        integer :: k
        code = 0
        do k = 1, size(pulse_shapes)
            if (trim(name) == trim(pulse_shapes(k))) code = k
        end do
    end function pulse_code

    !> Velocity change of a pulse of peak 1: Δv = peak x this factor
    !! (half-sine 2T/π, haversine T/2, triangle T/2, trapezoid T(1 - r),
    !! ramp T).
    pure real(wp) function pulse_dv_factor(shape, duration, frac) result(f)
        integer, intent(in) :: shape        !! pulse_halfsine .. pulse_ramp
        real(wp), intent(in) :: duration    !! T [s]
        real(wp), intent(in) :: frac        !! trapezoid: rise (= fall) time / T; otherwise unused
        select case (shape)
        case (pulse_halfsine); f = 2*duration/pi
        case (pulse_haversine, pulse_triangle); f = half*duration
        case (pulse_trapezoid); f = duration*(one - frac)
        case default; f = duration
        end select
    end function pulse_dv_factor

    !> The knots (t, a) of a pulse's piecewise-linear table: zero before
    !! the onset and after the end, velocity change peak x pulse_dv_factor.
    pure subroutine pulse_knots(shape, peak, duration, onset, frac, t, a)
        integer, intent(in) :: shape          !! pulse_halfsine .. pulse_ramp
        real(wp), intent(in) :: peak          !! the largest value (signed)
        real(wp), intent(in) :: duration      !! T > 0 [s]
        real(wp), intent(in) :: onset         !! start of the pulse, >= 0 [s]
        real(wp), intent(in) :: frac          !! triangle: time of the peak / T; trapezoid: rise time / T
        real(wp), allocatable, intent(out) :: t(:)   !! knot times, increasing [s]
        real(wp), allocatable, intent(out) :: a(:)   !! values at the knots
        real(wp), allocatable :: tau(:), y(:)
        integer :: k, n
        select case (shape)
        case (pulse_halfsine, pulse_haversine)
            n = sine_segments
            tau = [(duration*real(k, wp)/n, k=0, n)]
            if (shape == pulse_halfsine) then
                y = sin(pi*tau/duration)
            else
                y = sin(pi*tau/duration)**2
            end if
            y(1) = zero; y(n + 1) = zero
            y = y*(pulse_dv_factor(shape, duration, frac)/table_dv(tau, y))
        case (pulse_triangle)
            tau = [zero, frac*duration, duration]
            y = [zero, one, zero]
        case (pulse_trapezoid)
            tau = [zero, frac*duration, (one - frac)*duration, duration]
            y = [zero, one, one, zero]
        case default
            tau = [zero, ramp_edge*duration, duration, (one + ramp_edge)*duration]
            y = [zero, one, one, zero]
        end select
        t = onset + tau
        a = peak*y
        if (onset > zero) then
            t = [zero, t]
            a = [zero, a]
        end if
    end subroutine pulse_knots

    !> The integral of the linear interpolant of (t, a) from t(1) to t(n):
    !! a table's velocity change.
    pure real(wp) function table_dv(t, a) result(dv)
        real(wp), intent(in) :: t(:)   !! knot times, increasing [s]
        real(wp), intent(in) :: a(:)   !! values at the knots
        integer :: n
        n = size(t)
        dv = zero
        if (n > 1) dv = sum(half*(a(2:n) + a(1:n - 1))*(t(2:n) - t(1:n - 1)))
    end function table_dv

end module hn_pulses
