!> Applied forces and couples on bodies from time tables (impact forces,
!! pendulum loads): magnitude(t) times a fixed direction, in the body frame
!! or in R, through a point fixed in the body.
module hn_applied
    use hn_kinds, only: wp, zero
    use hn_tables, only: table_t, table_value
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t, add_point_force, add_couple
    implicit none
    private

    public :: applied_load_t, apply_applied_load, applied_vector

    integer, parameter, public :: applied_force = 1, applied_couple = 2
    integer, parameter, public :: frame_inertial = 0, frame_body = 1

    !> One applied force or couple.
    type :: applied_load_t
        integer :: body = 1                  !! body it acts on
        integer :: kind = applied_force      !! applied_force or applied_couple
        integer :: frame = frame_inertial    !! direction fixed in R or in the body
        real(wp) :: point(3) = zero          !! point of application, body frame from the mass centre [m]
        real(wp) :: direction(3) = zero      !! unit direction
        type(table_t) :: magnitude           !! [N] or [N m] against time [s]
    end type applied_load_t

contains

    !> The force or couple vector in R at time t.
    pure function applied_vector(al, kin, t) result(f)
        type(applied_load_t), intent(in) :: al   !! the applied load
        type(kinematics_t), intent(in) :: kin    !! kinematics of the tree
        real(wp), intent(in) :: t                !! time [s]
        real(wp) :: f(3)
        f = table_value(al%magnitude, t)*al%direction
        if (al%frame == frame_body) f = matmul(kin%s(:, :, al%body), f)
    end function applied_vector

    !> Add the load at time t to the body loads.
    pure subroutine apply_applied_load(al, kin, t, loads)
        type(applied_load_t), intent(in) :: al   !! the applied load
        type(kinematics_t), intent(in) :: kin    !! kinematics of the tree
        real(wp), intent(in) :: t                !! time [s]
        type(body_loads_t), intent(inout) :: loads !! body loads, the load added
        real(wp) :: f(3), p(3)
        integer :: k
        k = al%body
        f = applied_vector(al, kin, t)
        if (al%kind == applied_couple) then
            call add_couple(loads, k, f)
        else
            p = kin%r(:, k) + matmul(kin%s(:, :, k), al%point)
            call add_point_force(loads, k, kin%r(:, k), p, f)
        end if
    end subroutine apply_applied_load

end module hn_applied
