!> The abstract first-order system y' = g(t, y) that every integrator
!! advances.
module hn_ode
    use hn_kinds, only: wp, msglen
    implicit none
    private

    public :: ode_system_t

    !> A first-order system; extended by the model and by test problems.
    !! The last `nquad` components of y are quadratures: g never depends on
    !! them (integrators need not differentiate with respect to them).
    type, abstract :: ode_system_t
        integer :: nevals = 0   !! number of right-hand-side evaluations so far
        integer :: nquad = 0    !! trailing quadrature components of y
    contains
        procedure(rhs_interface), deferred :: rhs
    end type ode_system_t

    abstract interface
        !> dydt = g(t, y); stat /= 0 with errmsg when the state is invalid.
        subroutine rhs_interface(me, t, y, dydt, stat, errmsg)
            import :: ode_system_t, wp, msglen
            class(ode_system_t), intent(inout) :: me
            real(wp), intent(in) :: t
            real(wp), intent(in) :: y(:)
            real(wp), intent(out) :: dydt(:)
            integer, intent(out) :: stat
            character(len=msglen), intent(out) :: errmsg
        end subroutine rhs_interface
    end interface

end module hn_ode
