!> Contact of an ellipsoid on a body with a plane fixed in R or on a
!! body, and the contact law: the geometry (penetration, contact point,
!! penetration rate and tangential slip velocity, all closed form), the
!! normal force from a loading and an unloading force-penetration table
!! with damping, regularized Coulomb friction, and the energy the law
!! stores and the power it dissipates.
!!
!! Geometry. The ellipsoid has semi-axes a along its body's axes and
!! centre c in the body frame; the plane a point p and a unit normal n
!! pointing to the free side. The ellipsoid's extreme point towards the
!! plane (its support point along -n) is x = C - S diag(a)^2 S^T n / h with
!! h = |diag(a) S^T n| the support distance, and the penetration is
!! d = h - n . (C - P) (d > 0: inside). Its rate is d' = -n . v_rel, v_rel
!! the velocity of the ellipsoid's material point at x relative to the
!! plane's material point there (the support point's sliding along the
!! surface does not change d).
!!
!! Law. While d' >= 0 (loading) the elastic force is the loading table
!! f_l(d); while d' < 0 (unloading) it is the unloading table f_u(d), never
!! above f_l(d) (blank unloading table: f_u = f_l, elastic). The normal
!! force N = max(0, f + c d') never pulls. Stored energy U = integral of
!! f_l from 0 to d; the rest of the work N d' is dissipated (hysteresis
!! and damping). Friction F_t = -mu N v_t / max(|v_t|, v_s): Coulomb's
!! mu N beyond the slip velocity v_s, linear in v_t below it.
module hn_contact_geometry
    use hn_kinds, only: wp, zero, half
    use hn_kinematics, only: kinematics_t
    use hn_tables, only: table_t, table_value
    use hn_rotation, only: cross
    implicit none
    private

    public :: contact_t, contact_state_t, contact_geometry, normal_force, friction_force, table_integral

    !> One contact: an ellipsoid on a body against a plane.
    type :: contact_t
        character(len=12) :: name = ''
        integer :: body = 1                       !! body of the ellipsoid (reduced tree)
        integer :: plane_body = 0                 !! body of the plane (0 = R)
        real(wp) :: semi(3) = zero                !! semi-axes along the body axes [m]
        real(wp) :: centre(3) = zero              !! ellipsoid centre in the body frame, from its mass centre [m]
        real(wp) :: point(3) = zero               !! a point of the plane in its body's frame [m]
        real(wp) :: normal(3) = [zero, zero, 1.0_wp]   !! unit normal of the plane (to the free side), its body's frame
        integer :: load = 0                       !! loading table (index in the family's tables)
        integer :: unload = 0                     !! unloading table (0: the loading table, elastic)
        real(wp) :: damping = zero                !! normal damping [N s/m]
        real(wp) :: mu = zero                     !! friction coefficient
        real(wp) :: v_slip = 0.01_wp              !! slip velocity of full friction [m/s]
    end type contact_t

    !> Where a contact is at one instant.
    type :: contact_state_t
        real(wp) :: depth = zero        !! penetration d [m] (negative: the gap)
        real(wp) :: rate = zero         !! its rate d' [m/s]
        real(wp) :: point(3) = zero     !! contact point x (the ellipsoid's support point) in R [m]
        real(wp) :: normal(3) = zero    !! plane normal in R
        real(wp) :: vt(3) = zero        !! tangential slip velocity of the ellipsoid on the plane in R [m/s]
    end type contact_state_t

contains

    !> The geometry of contact c at the kinematics kin.
    pure subroutine contact_geometry(kin, c, g)
        type(kinematics_t), intent(in) :: kin        !! kinematics of the tree (body level)
        type(contact_t), intent(in) :: c             !! the contact
        type(contact_state_t), intent(out) :: g      !! its geometry
        real(wp) :: n(3), p(3), cen(3), w(3), h, vk(3), vp(3), vrel(3)
        associate (s => kin%s(:, :, c%body), r => kin%r(:, c%body))
            if (c%plane_body > 0) then
                n = matmul(kin%s(:, :, c%plane_body), c%normal)
                p = kin%r(:, c%plane_body) + matmul(kin%s(:, :, c%plane_body), c%point)
            else
                n = c%normal
                p = c%point
            end if
            cen = r + matmul(s, c%centre)
            w = c%semi*matmul(n, s)               ! diag(a) S^T n
            h = norm2(w)
            g%point = cen - matmul(s, c%semi*w)/h
            g%depth = h - dot_product(n, cen - p)
            g%normal = n
            vk = kin%v(:, c%body) + cross(kin%omega(:, c%body), g%point - r)
            vp = zero
            if (c%plane_body > 0) vp = kin%v(:, c%plane_body) + &
                                       cross(kin%omega(:, c%plane_body), g%point - kin%r(:, c%plane_body))
            vrel = vk - vp
            g%rate = -dot_product(n, vrel)
            g%vt = vrel + g%rate*n
        end associate
    end subroutine contact_geometry

    !> Normal force N >= 0 [N] at penetration d [m] and rate dd [m/s], and
    !! the elastic (loading-curve) force f_l [N]; zero out of contact.
    pure subroutine normal_force(c, tabs, d, dd, force, f_load)
        type(contact_t), intent(in) :: c            !! the contact
        type(table_t), intent(in) :: tabs(:)        !! the family's tables
        real(wp), intent(in) :: d                   !! penetration [m]
        real(wp), intent(in) :: dd                  !! its rate [m/s]
        real(wp), intent(out) :: force              !! normal force N [N]
        real(wp), intent(out) :: f_load             !! loading-curve force f_l(d) [N]
        real(wp) :: fe
        force = zero; f_load = zero
        if (d <= zero) return
        f_load = max(zero, table_value(tabs(c%load), d))
        fe = f_load
        if (dd < zero .and. c%unload > 0) fe = max(zero, min(table_value(tabs(c%unload), d), f_load))
        force = max(zero, fe + c%damping*dd)
    end subroutine normal_force

    !> Regularized Coulomb friction on the slip velocity vt [m/s] under the normal force n [N].
    pure function friction_force(c, n, vt) result(ft)
        type(contact_t), intent(in) :: c            !! the contact
        real(wp), intent(in) :: n                   !! normal force [N]
        real(wp), intent(in) :: vt(3)               !! tangential slip velocity [m/s]
        real(wp) :: ft(3)                           !! friction force on the ellipsoid [N]
        ft = -c%mu*n*vt/max(norm2(vt), c%v_slip)
    end function friction_force

    !> Integral of a piecewise-linear table from 0 to d (trapezoids; end
    !! values held outside the table, as table_value does).
    pure real(wp) function table_integral(tab, d) result(u)
        type(table_t), intent(in) :: tab            !! the table
        real(wp), intent(in) :: d                   !! upper limit (>= 0)
        real(wp) :: a, b
        integer :: i, n
        u = zero
        n = size(tab%t)
        ! below the first abscissa: the first value; the segments; beyond: the last value
        a = zero
        if (tab%t(1) > zero) then
            b = min(d, tab%t(1))
            u = u + tab%y(1)*(b - a)
            a = b
        end if
        do i = 1, n - 1
            if (a >= d) exit
            if (tab%t(i + 1) <= a) cycle
            b = min(d, tab%t(i + 1))
            u = u + half*(table_value(tab, a) + table_value(tab, b))*(b - a)
            a = b
        end do
        if (d > a) u = u + tab%y(n)*(d - a)
    end function table_integral

end module hn_contact_geometry
