!> Joint limits as one-way dampers on relative coordinates (eqs 12-13):
!! Q = -C xdot, acting only while the coordinate moves away from its
!! neutral value towards a limit, with C = C0 inside [Xmin, Xmax] and
!! C = C0 + C1 |X - Xlimit| beyond the limit crossed.
module hn_joint_limits
    use hn_kinds, only: wp, zero
    implicit none
    private

    public :: joint_limit_t, limit_damping, limit_force

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

contains

    !> Damping coefficient C(X) (eq 13): continuous at both limits.
    pure real(wp) function limit_damping(lim, x) result(c)
        type(joint_limit_t), intent(in) :: lim
        real(wp), intent(in) :: x
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
        type(joint_limit_t), intent(in) :: lim
        real(wp), intent(in) :: x, xd
        if (xd*(x - lim%xneutral) > zero) then
            q = -limit_damping(lim, x)*xd
        else
            q = zero
        end if
    end function limit_force

end module hn_joint_limits
