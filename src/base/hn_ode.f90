!> The abstract first-order system y' = g(t, y) that every integrator
!! advances, with an optional second-order structure the stiff
!! integrators use: y = (x, xdot, quadratures) and g = (xdot, xddot, ...),
!! and a tangent xddot ~ -M^-1 (K dx + C dxdot) from the system's physics.
module hn_ode
    use hn_kinds, only: wp, msglen
    use hn_status, only: stat_bad_input
    implicit none
    private

    public :: ode_system_t

    !> A first-order system; extended by the model and by test problems.
    !! The last `nquad` components of y are quadratures: g never depends on
    !! them (integrators need not differentiate with respect to them).
    type, abstract :: ode_system_t
        integer :: nevals = 0   !! number of right-hand-side evaluations so far
        integer :: nquad = 0    !! trailing quadrature components of y
        integer :: nsecond = 0  !! > 0: y = (x, xdot, quadratures) with x of this size and g = (xdot, ...)
        logical :: has_tangent = .false.  !! second_order_tangent is available (else Jacobians by differences)
    contains
        procedure(rhs_interface), deferred :: rhs
        procedure :: second_order_tangent => no_tangent
    end type ode_system_t

    abstract interface
        !> dydt = g(t, y); stat /= 0 with errmsg when the state is invalid.
        subroutine rhs_interface(me, t, y, dydt, stat, errmsg)
            import :: ode_system_t, wp, msglen
            class(ode_system_t), intent(inout) :: me
            real(wp), intent(in) :: t                      !! time [s]
            real(wp), intent(in) :: y(:)                   !! state; second order: (x, xdot, quadratures)
            real(wp), intent(out) :: dydt(:)               !! g(t, y), the size of y
            integer, intent(out) :: stat                   !! stat_ok, or a status code from hn_status
            character(len=msglen), intent(out) :: errmsg   !! what is wrong ('' when stat_ok)
        end subroutine rhs_interface
    end interface

contains

    !> Mass M, stiffness K and damping C (nsecond x nsecond) of a
    !! second-order system at (t, y): the Jacobian of xddot is approximated
    !! by d(xddot)/dx = -M^-1 K, d(xddot)/dxdot = -M^-1 C. This default says
    !! the system has none.
    subroutine no_tangent(me, t, y, mass, stiffness, damping, stat, errmsg)
        class(ode_system_t), intent(inout) :: me
        real(wp), intent(in) :: t                      !! time
        real(wp), intent(in) :: y(:)                   !! state
        real(wp), intent(out) :: mass(:, :)            !! (nsecond, nsecond) M; zero here
        real(wp), intent(out) :: stiffness(:, :)       !! (nsecond, nsecond) K; zero here
        real(wp), intent(out) :: damping(:, :)         !! (nsecond, nsecond) C; zero here
        integer, intent(out) :: stat                   !! stat_bad_input: no tangent
        character(len=msglen), intent(out) :: errmsg   !! says the system has no tangent
        mass = 0; stiffness = 0; damping = 0
        stat = stat_bad_input
        errmsg = 'this system has no second-order tangent'
    end subroutine no_tangent

end module hn_ode
