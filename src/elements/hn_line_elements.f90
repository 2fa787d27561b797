!> Point-to-point elements acting along the line between an attachment point
!! on one body and one on another: linear spring-dampers, ligaments
!! (tension only, F = l1 d + l2 d^n, eq 10) and muscles (tension only,
!! F = m1 d + m2 d', eq 11).
module hn_line_elements
    use hn_kinds, only: wp, zero, one
    use hn_rotation, only: cross, norm3
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t, add_point_force
    implicit none
    private

    public :: line_geometry_t, line_geometry, apply_line_tension, attachment_point
    public :: spring_t, spring_tension, ligament_t, ligament_tension, ligament_energy
    public :: muscle_t, muscle_tension

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
        real(wp) :: free_length = -one           !! unstretched length [m]; negative: the neutral length
        real(wp) :: stiffness = zero             !! [N/m]
        real(wp) :: damping = zero               !! [N s/m]
    end type spring_t

    !> Ligament (eq 10): tension-only nonlinear band, F = l1 d + l2 d^n for
    !! stretch d = L - L0 > 0, zero when slack.
    type :: ligament_t
        character(len=12) :: name = ''
        integer :: body_a = 0, body_b = 0
        real(wp) :: point_a(3) = zero, point_b(3) = zero  !! attachments, body frames [m]
        real(wp) :: slack_length = -one   !! L0 [m]; negative: the neutral length
        real(wp) :: l1 = zero             !! linear coefficient [N/m]
        real(wp) :: l2 = zero             !! nonlinear coefficient [N/m^n]
        real(wp) :: n = 2.0_wp            !! exponent
    end type ligament_t

    !> Muscle (eq 11): tension-only two-parameter viscoelastic element,
    !! F = max(0, m1 d + m2 d' + a(t) Fmax), d = L - L0; it never pushes.
    !! The activation a(t) in [0, 1] (a table, beyond the paper) is optional.
    type :: muscle_t
        character(len=12) :: name = ''
        integer :: body_a = 0, body_b = 0
        real(wp) :: point_a(3) = zero, point_b(3) = zero
        real(wp) :: rest_length = -one    !! L0 [m]; negative: the neutral length
        real(wp) :: m1 = zero             !! stiffness [N/m]
        real(wp) :: m2 = zero             !! damping [N s/m]
        real(wp) :: fmax = zero           !! force at full activation [N]
        integer :: activation = 0         !! table number of a(t); 0 = passive
    end type muscle_t

contains

    !> Ligament tension (eq 10) at length L.
    pure real(wp) function ligament_tension(g, length) result(t)
        type(ligament_t), intent(in) :: g
        real(wp), intent(in) :: length
        real(wp) :: d
        d = length - g%slack_length
        if (d > zero) then
            t = g%l1*d + g%l2*d**g%n
        else
            t = zero
        end if
    end function ligament_tension

    !> Elastic energy stored in a ligament at length L.
    pure real(wp) function ligament_energy(g, length) result(u)
        type(ligament_t), intent(in) :: g
        real(wp), intent(in) :: length
        real(wp) :: d
        d = max(zero, length - g%slack_length)
        u = 0.5_wp*g%l1*d**2 + g%l2*d**(g%n + one)/(g%n + one)
    end function ligament_energy

    !> Muscle tension (eq 11, tension only) at length L, rate L' and activation a.
    pure real(wp) function muscle_tension(m, length, rate, act) result(t)
        type(muscle_t), intent(in) :: m
        real(wp), intent(in) :: length, rate, act
        t = max(zero, m%m1*(length - m%rest_length) + m%m2*rate + act*m%fmax)
    end function muscle_tension

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
