!> Generalized stiffness K and damping C of the model's elements: the
!! tangent of the element loads, mapped through the joint columns (the
!! partial velocities) onto the active coordinates. With a_ij they give the
!! structured Jacobian of the equations of motion used by the stiff
!! integrators: d(xddot)/dx ~ -a^-1 K, d(xddot)/dxdot ~ -a^-1 C.
!!
!! Each element has a deformation rate that is linear in xdot,
!! delta' = B xdot (B exact: the element's geometry), and loads whose
!! generalized forces are Q = -B^T s(delta, delta'). Then
!!   K = B^T (ds/d delta) B,   C = B^T (ds/d delta') B,
!! leaving out the terms of dB/dx s (geometric stiffness) and the
!! dependence of a_ij, gravity and the velocity terms on x: an approximate
!! Jacobian, which the Rosenbrock-W method tolerates by construction. The
!! tangent of each element's law ds/d delta, ds/d delta' is a central
!! difference of the law itself, so any present or future law gets one.
!!   discs         delta = q (6 deformations), s = disc_resultants(q, qd)
!!   line elements delta = length L, s = tension T(L, L')
!!   joint dampers the generalized force on their coordinate directly
!! B of an element is nonzero only on the coordinates between its two
!! bodies: for a common ancestor's coordinate the two ends move as one
!! rigid body and the contributions cancel exactly. Each family adds its
!! own terms (its `add_tangent` binding, hn_element_family); this module
!! visits the families once each, in the registry's order.
module hn_jacobian
    use hn_kinds, only: wp, zero
    use hn_model, only: model_t
    use hn_kinematics, only: kinematics_t
    use hn_element_family, only: tangent_work_t, tangent_work
    implicit none
    private

    public :: generalized_tangent

contains

    !> K and C (n x n, all active coordinates) of every element switched on,
    !! for the kinematics kin of the state (x, xd) at time t (kin from
    !! body_kinematics or partial_velocities: joint columns filled).
    pure subroutine generalized_tangent(model, kin, t, x, xd, kgen, cgen)
        type(model_t), intent(in) :: model      !! the model (elements and the families switched on)
        type(kinematics_t), intent(in) :: kin   !! kinematics of (x, xd): joint columns filled
        real(wp), intent(in) :: t               !! time [s] (for the muscles' activation)
        real(wp), intent(in) :: x(:)            !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)           !! their rates [m/s, rad/s]
        real(wp), intent(out) :: kgen(:, :)     !! (n,n) generalized stiffness [N/m, N m/rad, ...]
        real(wp), intent(out) :: cgen(:, :)     !! (n,n) generalized damping
        integer :: f
        type(tangent_work_t) :: tw   ! scratch of the element terms, sized once here rather than in every element's call
        tw = tangent_work(max(size(kgen, 1), 1))
        kgen = zero
        cgen = zero
        do f = 1, size(model%family)
            if (model%family_on(f)) call model%family(f)%f%add_tangent(model%tree, kin, t, x, xd, kgen, cgen, tw)
        end do
    end subroutine generalized_tangent

end module hn_jacobian
