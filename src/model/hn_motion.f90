!> Prescribed motion of a coordinate: x(t), xdot(t), xddot(t) from a
!! constant, an acceleration table (piecewise linear, integrated exactly),
!! a rate table (a velocity or angular velocity, piecewise linear,
!! integrated exactly to the position or angle), a position table (natural
!! cubic spline) or a harmonic function.
module hn_motion
    use hn_kinds, only: wp, zero, half
    use hn_tables, only: table_t, table_set, table_segment, spline_t, spline_set, spline_eval
    implicit none
    private

    public :: motion_t, motion_constant, motion_accel_table, motion_position_table
    public :: motion_harmonic, motion_rate_table, motion_eval

    integer, parameter, public :: motion_kind_constant = 1, motion_kind_accel = 2, &
                                  motion_kind_position = 3, motion_kind_harmonic = 4, &
                                  motion_kind_rate = 5

    !> The time history of one prescribed coordinate.
    type :: motion_t
        integer :: kind = motion_kind_constant
        real(wp) :: x0 = zero      !! constant value, or position at the first table time
        real(wp) :: v0 = zero      !! velocity at the first table time (acceleration table)
        real(wp) :: amp = zero, freq = zero, phase = zero  !! harmonic: x0 + amp sin(freq t + phase)
        type(table_t) :: acc       !! acceleration table (a rate table: the rates)
        real(wp), allocatable :: xk(:), vk(:)  !! position and velocity at the table knots
        type(spline_t) :: pos      !! position spline
    end type motion_t

contains

    !> A coordinate held at value x0.
    pure function motion_constant(x0) result(m)
        real(wp), intent(in) :: x0   !! the value held [m or rad]
        type(motion_t) :: m
        m%kind = motion_kind_constant
        m%x0 = x0
    end function motion_constant

    !> Piecewise-linear acceleration table a(t) with position x0 and velocity
    !! v0 at t(1); integrated exactly. Outside the table the end acceleration
    !! holds. stat = stat_bad_table when the times do not increase.
    pure subroutine motion_accel_table(m, t, a, x0, v0, stat)
        type(motion_t), intent(out) :: m   !! the motion (knot positions and velocities filled)
        real(wp), intent(in) :: t(:)       !! table times, strictly increasing [s]
        real(wp), intent(in) :: a(:)       !! accelerations at t [m/s^2 or rad/s^2]
        real(wp), intent(in) :: x0         !! position at t(1) [m or rad]
        real(wp), intent(in) :: v0         !! velocity at t(1) [m/s or rad/s]
        integer, intent(out) :: stat       !! stat_ok, or stat_bad_table (from table_set)
        integer :: i, n
        real(wp) :: h, s
        m%kind = motion_kind_accel
        m%x0 = x0; m%v0 = v0
        call table_set(m%acc, t, a, stat)
        if (stat /= 0) return
        n = size(t)
        allocate (m%xk(n), m%vk(n))
        m%xk(1) = x0; m%vk(1) = v0
        do i = 1, n - 1
            h = t(i + 1) - t(i)
            s = (a(i + 1) - a(i))/h
            m%vk(i + 1) = m%vk(i) + a(i)*h + half*s*h**2
            m%xk(i + 1) = m%xk(i) + m%vk(i)*h + half*a(i)*h**2 + s*h**3/6.0_wp
        end do
    end subroutine motion_accel_table

    !> Piecewise-linear rate table w(t) (a velocity, or an angular velocity
    !! about the coordinate's axis) with position x0 at t(1), integrated
    !! exactly: x(t) = x0 + int w, xdot = w(t), xddot = the segment's slope.
    !! Before the table the first rate holds, after it the last (the
    !! position keeps growing at that rate). stat = stat_bad_table when the
    !! times do not increase.
    pure subroutine motion_rate_table(m, t, w, x0, stat)
        type(motion_t), intent(out) :: m   !! the motion (knot positions filled)
        real(wp), intent(in) :: t(:)       !! table times, strictly increasing [s]
        real(wp), intent(in) :: w(:)       !! rates at t [m/s or rad/s]
        real(wp), intent(in) :: x0         !! position at t(1) [m or rad]
        integer, intent(out) :: stat       !! stat_ok, or stat_bad_table (from table_set)
        integer :: i, n
        m%kind = motion_kind_rate
        m%x0 = x0
        call table_set(m%acc, t, w, stat)
        if (stat /= 0) return
        n = size(t)
        allocate (m%xk(n))
        m%xk(1) = x0
        do i = 1, n - 1
            m%xk(i + 1) = m%xk(i) + half*(w(i) + w(i + 1))*(t(i + 1) - t(i))
        end do
    end subroutine motion_rate_table

    !> Position table x(t) through a natural cubic spline.
    pure subroutine motion_position_table(m, t, x, stat)
        type(motion_t), intent(out) :: m   !! the motion
        real(wp), intent(in) :: t(:)       !! table times, strictly increasing [s]
        real(wp), intent(in) :: x(:)       !! positions at t [m or rad]
        integer, intent(out) :: stat       !! stat_ok, or stat_bad_table (from spline_set)
        m%kind = motion_kind_position
        call spline_set(m%pos, t, x, stat)
    end subroutine motion_position_table

    !> x = x0 + amp sin(freq t + phase).
    pure function motion_harmonic(x0, amp, freq, phase) result(m)
        real(wp), intent(in) :: x0      !! mean value [m or rad]
        real(wp), intent(in) :: amp     !! amplitude [m or rad]
        real(wp), intent(in) :: freq    !! circular frequency [rad/s]
        real(wp), intent(in) :: phase   !! phase at t = 0 [rad]
        type(motion_t) :: m
        m%kind = motion_kind_harmonic
        m%x0 = x0; m%amp = amp; m%freq = freq; m%phase = phase
    end function motion_harmonic

    !> Position, velocity and acceleration at time t.
    pure subroutine motion_eval(m, t, x, xd, xdd)
        type(motion_t), intent(in) :: m   !! the motion
        real(wp), intent(in) :: t         !! time [s]
        real(wp), intent(out) :: x        !! position [m or rad]
        real(wp), intent(out) :: xd       !! velocity [m/s or rad/s]
        real(wp), intent(out) :: xdd      !! acceleration [m/s^2 or rad/s^2]
        integer :: i, n
        real(wp) :: tau, s
        select case (m%kind)
        case (motion_kind_accel)
            n = size(m%acc%t)
            if (n == 1 .or. t <= m%acc%t(1)) then
                tau = t - m%acc%t(1)
                xdd = m%acc%y(1)
                xd = m%vk(1) + xdd*tau
                x = m%xk(1) + m%vk(1)*tau + half*xdd*tau**2
            else if (t >= m%acc%t(n)) then
                tau = t - m%acc%t(n)
                xdd = m%acc%y(n)
                xd = m%vk(n) + xdd*tau
                x = m%xk(n) + m%vk(n)*tau + half*xdd*tau**2
            else
                i = table_segment(m%acc%t, t)
                tau = t - m%acc%t(i)
                s = (m%acc%y(i + 1) - m%acc%y(i))/(m%acc%t(i + 1) - m%acc%t(i))
                xdd = m%acc%y(i) + s*tau
                xd = m%vk(i) + m%acc%y(i)*tau + half*s*tau**2
                x = m%xk(i) + m%vk(i)*tau + half*m%acc%y(i)*tau**2 + s*tau**3/6.0_wp
            end if
        case (motion_kind_rate)
            n = size(m%acc%t)
            if (n == 1 .or. t <= m%acc%t(1) .or. t >= m%acc%t(n)) then
                i = merge(n, 1, t >= m%acc%t(n))      ! the end rate holds outside the table
                xdd = zero
                xd = m%acc%y(i)
                x = m%xk(i) + xd*(t - m%acc%t(i))
            else
                i = table_segment(m%acc%t, t)
                tau = t - m%acc%t(i)
                xdd = (m%acc%y(i + 1) - m%acc%y(i))/(m%acc%t(i + 1) - m%acc%t(i))
                xd = m%acc%y(i) + xdd*tau
                x = m%xk(i) + m%acc%y(i)*tau + half*xdd*tau**2
            end if
        case (motion_kind_position)
            call spline_eval(m%pos, t, x, xd, xdd)
        case (motion_kind_harmonic)
            x = m%x0 + m%amp*sin(m%freq*t + m%phase)
            xd = m%amp*m%freq*cos(m%freq*t + m%phase)
            xdd = -m%amp*m%freq**2*sin(m%freq*t + m%phase)
        case default
            x = m%x0; xd = zero; xdd = zero
        end select
    end subroutine motion_eval

end module hn_motion
