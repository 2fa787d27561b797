!> Applied loads on the bodies: a resultant force through each mass centre,
!! a moment about it, and generalized forces acting directly on coordinates
!! (one-way joint dampers act that way, eq 12).
module hn_loads
    use hn_kinds, only: wp, zero
    implicit none
    private

    public :: body_loads_t, loads_allocate, loads_clear, add_point_force, add_couple
    public :: add_force_pair

    !> Resultant applied loads, vectors in R components.
    type :: body_loads_t
        real(wp), allocatable :: force(:, :)   !! (3,nb) force through the mass centre [N]
        real(wp), allocatable :: moment(:, :)  !! (3,nb) moment about the mass centre [N m]
        real(wp), allocatable :: q(:)          !! (n) generalized forces on coordinates [N or N m]
    end type body_loads_t

contains

    !> Allocate zeroed loads for nb bodies and n coordinates.
    pure subroutine loads_allocate(loads, nb, n)
        type(body_loads_t), intent(out) :: loads   !! allocated and zero
        integer, intent(in) :: nb                  !! number of bodies
        integer, intent(in) :: n                   !! number of coordinates (at least 1 entry is allocated)
        allocate (loads%force(3, nb), loads%moment(3, nb), loads%q(max(n, 1)))
        call loads_clear(loads)
    end subroutine loads_allocate

    !> Set every load to zero.
    pure subroutine loads_clear(loads)
        type(body_loads_t), intent(inout) :: loads   !! allocated loads, set to zero
        loads%force = zero
        loads%moment = zero
        loads%q = zero
    end subroutine loads_clear

    !> Add force f acting at point `point` (R) on body k whose mass centre is rk.
    pure subroutine add_point_force(loads, k, rk, point, f)
        type(body_loads_t), intent(inout) :: loads   !! the loads the force is added to
        integer, intent(in) :: k                     !! the body (0, the inertial frame: nothing added)
        real(wp), intent(in) :: rk(3)                !! its mass centre in R [m]
        real(wp), intent(in) :: point(3)             !! point of application in R [m]
        real(wp), intent(in) :: f(3)                 !! the force in R [N]
        real(wp) :: d(3)
        if (k < 1) return                     ! body 0 is the inertial frame
        d = point - rk
        loads%force(:, k) = loads%force(:, k) + f
        ! (point - rk) x f written out: this is the innermost call of every element
        loads%moment(1, k) = loads%moment(1, k) + (d(2)*f(3) - d(3)*f(2))
        loads%moment(2, k) = loads%moment(2, k) + (d(3)*f(1) - d(1)*f(3))
        loads%moment(3, k) = loads%moment(3, k) + (d(1)*f(2) - d(2)*f(1))
    end subroutine add_point_force

    !> Add a couple c to body k.
    pure subroutine add_couple(loads, k, c)
        type(body_loads_t), intent(inout) :: loads   !! the loads the couple is added to
        integer, intent(in) :: k                     !! the body (0, the inertial frame: nothing added)
        real(wp), intent(in) :: c(3)                 !! the couple in R [N m]
        if (k < 1) return
        loads%moment(:, k) = loads%moment(:, k) + c
    end subroutine add_couple

    !> Equal and opposite force and couple at one point: (f, c) on body kb,
    !! (-f, -c) on body ka. Such a pair does no net work in any rigid motion
    !! of the two bodies together.
    pure subroutine add_force_pair(loads, ka, ra, kb, rb, point, f, c)
        type(body_loads_t), intent(inout) :: loads   !! the loads the pair is added to
        integer, intent(in) :: ka                    !! body that receives (-f, -c) (0 = inertial frame)
        integer, intent(in) :: kb                    !! body that receives (f, c) (0 = inertial frame)
        real(wp), intent(in) :: ra(3)                !! mass centre of body ka in R [m]
        real(wp), intent(in) :: rb(3)                !! mass centre of body kb in R [m]
        real(wp), intent(in) :: point(3)             !! common point of application in R [m]
        real(wp), intent(in) :: f(3)                 !! force on body kb in R [N]
        real(wp), intent(in) :: c(3)                 !! couple on body kb in R [N m]
        call add_point_force(loads, kb, rb, point, f)
        call add_couple(loads, kb, c)
        call add_point_force(loads, ka, ra, point, -f)
        call add_couple(loads, ka, -c)
    end subroutine add_force_pair

end module hn_loads
