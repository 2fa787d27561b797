!> Point-to-point elements acting along the line between an attachment point
!! on one body and one on another: linear spring-dampers, ligaments
!! (tension only, F = l1 d + l2 d^n, eq 10) and muscles (tension only,
!! F = m1 d + m2 d', eq 11).
module hn_line_elements
    use hn_kinds, only: wp, zero
    use hn_rotation, only: cross, norm3
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t, add_point_force
    implicit none
    private

    public :: line_geometry_t, line_geometry, apply_line_tension, attachment_point
    public :: spring_t, spring_tension

    !> Where a line element is and how fast it lengthens.
    type :: line_geometry_t
        real(wp) :: pa(3) = zero, pb(3) = zero  !! attachment points in R [m]
        real(wp) :: length = zero                !! current length [m]
        real(wp) :: rate = zero                  !! lengthening rate [m/s]
        real(wp) :: unit(3) = zero               !! unit vector from a to b
    end type line_geometry_t

    !> Linear spring-damper between two bodies (tension positive).
    type :: spring_t
        integer :: body_a = 0, body_b = 0        !! bodies (0 = inertial frame)
        real(wp) :: point_a(3) = zero, point_b(3) = zero !! attachment in body frames, from the mass centre [m]
        real(wp) :: free_length = zero           !! unstretched length [m]
        real(wp) :: stiffness = zero             !! [N/m]
        real(wp) :: damping = zero               !! [N s/m]
    end type spring_t

contains

    !> Position and velocity (R) of a point fixed in body k at body-frame
    !! offset c from the mass centre (k = 0: c is a point of R).
    pure subroutine attachment_point(kin, k, c, p, v)
        type(kinematics_t), intent(in) :: kin
        integer, intent(in) :: k
        real(wp), intent(in) :: c(3)
        real(wp), intent(out) :: p(3), v(3)
        real(wp) :: d(3)
        if (k == 0) then
            p = c; v = zero
        else
            d = matmul(kin%s(:, :, k), c)
            p = kin%r(:, k) + d
            v = kin%v(:, k) + cross(kin%omega(:, k), d)
        end if
    end subroutine attachment_point

    !> Geometry of the line from point ca on body ka to point cb on body kb.
    pure subroutine line_geometry(kin, ka, ca, kb, cb, g)
        type(kinematics_t), intent(in) :: kin
        integer, intent(in) :: ka, kb
        real(wp), intent(in) :: ca(3), cb(3)
        type(line_geometry_t), intent(out) :: g
        real(wp) :: va(3), vb(3), d(3)
        call attachment_point(kin, ka, ca, g%pa, va)
        call attachment_point(kin, kb, cb, g%pb, vb)
        d = g%pb - g%pa
        g%length = norm3(d)
        if (g%length > zero) then
            g%unit = d/g%length
        else
            g%unit = zero
        end if
        g%rate = dot_product(g%unit, vb - va)
    end subroutine line_geometry

    !> Apply a tension (positive pulls the ends together) along the line.
    pure subroutine apply_line_tension(loads, kin, ka, kb, g, tension)
        type(body_loads_t), intent(inout) :: loads
        type(kinematics_t), intent(in) :: kin
        integer, intent(in) :: ka, kb
        type(line_geometry_t), intent(in) :: g
        real(wp), intent(in) :: tension
        if (ka > 0) call add_point_force(loads, ka, kin%r(:, ka), g%pa, tension*g%unit)
        if (kb > 0) call add_point_force(loads, kb, kin%r(:, kb), g%pb, -tension*g%unit)
    end subroutine apply_line_tension

    !> Spring-damper tension k (L - L0) + c L'.
    pure real(wp) function spring_tension(s, length, rate) result(t)
        type(spring_t), intent(in) :: s
        real(wp), intent(in) :: length, rate
        t = s%stiffness*(length - s%free_length) + s%damping*rate
    end function spring_tension

end module hn_line_elements
