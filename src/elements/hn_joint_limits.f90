!> Joint limits as one-way dampers on relative coordinates (eqs 12-13):
!! Q = -C xdot, acting only while the coordinate moves away from its
!! neutral value towards a limit, with C = C0 inside [Xmin, Xmax] and
!! C = C0 + C1 |X - Xlimit| beyond the limit crossed. Beyond the paper:
!! joint resistance past the physiological range of motion (ROM cards), an
!! elastic moment that stiffens with the excess e,
!! Q = -K t0 (exp(e/t0) - 1) (slope K at the edge of the range, stiffening
!! by e per t0), standing for the ligaments and facets that stop a real
!! joint; and the check of a response against the ranges.
module hn_joint_limits
    use hn_kinds, only: wp, zero, one, deg
    implicit none
    private

    public :: joint_limit_t, limit_damping, limit_force
    public :: joint_range_t, range_excess, range_moment, range_energy, range_warnings, range_track

    !> Excess beyond a joint's physiological range tolerated before a run is
    !! flagged: 5 deg, about the spread of measured segmental ranges.
    real(wp), parameter, public :: range_margin = 5.0_wp*deg

    !> One joint-limit damper.
    type :: joint_limit_t
        integer :: body = 0          !! body whose coordinate is limited
        integer :: local = 0         !! local coordinate 1..6
        integer :: dof = 0           !! active coordinate number
        real(wp) :: xmin = zero, xmax = zero   !! limits [m or rad]
        real(wp) :: xneutral = zero  !! neutral value [m or rad]
        real(wp) :: c0 = zero        !! damping inside the range [N s/m or N m s/rad]
        real(wp) :: c1 = zero        !! ramp of damping beyond a limit, per unit excess
    end type joint_limit_t

    !> Resistance of one joint rotation beyond its physiological range.
    type :: joint_range_t
        character(len=16) :: label = ''   !! joint and coordinate, for messages (C5 RY)
        integer :: dof = 0                !! active coordinate number
        real(wp) :: xmin = zero, xmax = zero   !! physiological range [rad]
        real(wp) :: k = zero              !! stiffness at the edge of the range [N m/rad]
        real(wp) :: t0 = 0.1_wp           !! excess over which the stiffness grows e-fold [rad]
    end type joint_range_t

contains

    !> Damping coefficient C(X) (eq 13): continuous at both limits.
    pure real(wp) function limit_damping(lim, x) result(c)
        type(joint_limit_t), intent(in) :: lim   !! the joint-limit damper
        real(wp), intent(in) :: x                !! its coordinate [m or rad]
        if (x > lim%xmax) then
            c = lim%c0 + lim%c1*(x - lim%xmax)
        else if (x < lim%xmin) then
            c = lim%c0 + lim%c1*(lim%xmin - x)
        else
            c = lim%c0
        end if
    end function limit_damping

    !> Generalized force (eq 12): -C xdot when the motion carries the
    !! coordinate away from neutral (towards a limit), zero otherwise.
    pure real(wp) function limit_force(lim, x, xd) result(q)
        type(joint_limit_t), intent(in) :: lim   !! the joint-limit damper
        real(wp), intent(in) :: x                !! its coordinate [m or rad]
        real(wp), intent(in) :: xd               !! its rate [m/s or rad/s]
        if (xd*(x - lim%xneutral) > zero) then
            q = -limit_damping(lim, x)*xd
        else
            q = zero
        end if
    end function limit_force

    !> Excess of coordinate x beyond the range: positive above xmax,
    !! negative below xmin, zero inside [rad].
    elemental real(wp) function range_excess(r, x) result(e)
        type(joint_range_t), intent(in) :: r   !! the range
        real(wp), intent(in) :: x              !! coordinate [rad]
        e = max(zero, x - r%xmax) + min(zero, x - r%xmin)
    end function range_excess

    !> Generalized force of the range resistance: -sign(e) K t0 (exp(|e|/t0) - 1).
    elemental real(wp) function range_moment(r, x) result(q)
        type(joint_range_t), intent(in) :: r   !! the range
        real(wp), intent(in) :: x              !! coordinate [rad]
        real(wp) :: e
        e = range_excess(r, x)
        q = -sign(one, e)*r%k*r%t0*(exp(abs(e)/r%t0) - one)
        if (e == zero) q = zero
    end function range_moment

    !> Elastic energy of the range resistance, K t0 (t0 (exp(|e|/t0) - 1) - |e|).
    elemental real(wp) function range_energy(r, x) result(u)
        type(joint_range_t), intent(in) :: r   !! the range
        real(wp), intent(in) :: x              !! coordinate [rad]
        real(wp) :: e
        e = abs(range_excess(r, x))
        u = r%k*r%t0*(r%t0*(exp(e/r%t0) - one) - e)
    end function range_energy

    !> Keep the largest |excess| of every range and its time.
    pure subroutine range_track(ranges, x, t, peak, tpeak)
        type(joint_range_t), intent(in) :: ranges(:)  !! the ranges
        real(wp), intent(in) :: x(:)                  !! active coordinates
        real(wp), intent(in) :: t                     !! time [s]
        real(wp), intent(inout) :: peak(:)       !! largest |excess| so far [rad]
        real(wp), intent(inout) :: tpeak(:)      !! when [s]
        real(wp) :: e
        integer :: k
        do k = 1, size(ranges)
            e = abs(range_excess(ranges(k), x(ranges(k)%dof)))
            if (e > peak(k)) then
                peak(k) = e; tpeak(k) = t
            end if
        end do
    end subroutine range_track

    !> Warnings for the joints whose largest excess beyond the range
    !! (peak(k) at time tpeak(k)) is more than `margin` [rad].
    pure function range_warnings(ranges, peak, tpeak, margin) result(lines)
        type(joint_range_t), intent(in) :: ranges(:)  !! the ranges
        real(wp), intent(in) :: peak(:)               !! largest |excess| of each [rad]
        real(wp), intent(in) :: tpeak(:)              !! when [s]
        real(wp), intent(in) :: margin                !! allowed excess [rad]
        character(len=160), allocatable :: lines(:)
        character(len=160) :: w
        integer :: k
        allocate (lines(0))
        do k = 1, size(ranges)
            if (peak(k) <= margin) cycle
            write (w, '(a,a,a,f6.1,a,f6.1,a,f6.1,a,f7.1,a,f5.1,a)') 'WARNING: joint ', trim(ranges(k)%label), &
                ' went ', peak(k)/deg, ' deg past its physiological range [', ranges(k)%xmin/deg, ', ', &
                ranges(k)%xmax/deg, '] deg at ', 1000*tpeak(k), ' ms (margin ', margin/deg, ' deg)'
            lines = [character(len=160) :: lines, w]
        end do
    end function range_warnings

end module hn_joint_limits
