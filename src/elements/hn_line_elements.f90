!> Point-to-point elements acting along the line between an attachment point
!! on one body and one on another. Every kind shares one attachment record,
!! `line_attach_t` (name, bodies, points, free length), and the procedures
!! over it (geometry, loads, neutral lengths); each kind adds its law:
!! linear spring-dampers, ligaments (tension only, F = l1 d + l2 d^n, eq 10)
!! and muscles (tension only, F = m1 d + m2 d', eq 11, or Hill-type).
!!
!! A muscle may run through via points fixed on the bodies it passes (the
!! vertebrae along its course), as real neck muscles follow the spine
!! instead of bowstringing across it: its length is that of the polyline
!! origin - via points - insertion, and its tension acts along every
!! segment, pulling each point towards its neighbours on the path.
module hn_line_elements
    use hn_kinds, only: wp, zero, one
    use hn_rotation, only: norm3
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t, add_point_force
    use hn_muscle, only: hill_t, hill_force
    implicit none
    private

    public :: line_attach_t, line_geometry_t, line_geometry, line_geometries, apply_line_tension, &
              apply_line_tensions, attachment_point, set_neutral_lengths, path_points
    public :: spring_t, spring_tension, spring_energy, ligament_t, ligament_tension, ligament_energy
    public :: muscle_t, muscle_tension, muscle_law_value, muscle_geometries, apply_muscle_tensions, muscle_path_points
    public :: mirror_muscles, sagittal_state, muscle_tensions

    integer, parameter, public :: muscle_passive = 1, muscle_hill = 2   !! muscle laws: eq 11, Hill-type
    integer, parameter, public :: max_via = 8   !! via points of one muscle path

    !> Where a line element is attached: the part every kind shares.
    type :: line_attach_t
        character(len=12) :: name = ''
        integer :: body_a = 0, body_b = 0                !! bodies (0 = inertial frame)
        real(wp) :: point_a(3) = zero, point_b(3) = zero !! attachments in body frames, from the mass centre [m]
        real(wp) :: length0 = -one                       !! free (slack, rest) length [m]; negative: the neutral length
    end type line_attach_t

    !> Where a line element is and how fast it lengthens.
    type :: line_geometry_t
        real(wp) :: pa(3) = zero, pb(3) = zero  !! attachment points in R [m]
        real(wp) :: length = zero                !! current length [m]
        real(wp) :: rate = zero                  !! lengthening rate [m/s]
        real(wp) :: unit(3) = zero               !! unit vector from a to b
    end type line_geometry_t

    !> Linear spring-damper between two bodies (tension positive).
    type, extends(line_attach_t) :: spring_t
        real(wp) :: stiffness = zero             !! [N/m]
        real(wp) :: damping = zero               !! [N s/m]
    end type spring_t

    !> Ligament (eq 10): tension-only nonlinear band, F = l1 d + l2 d^n for
    !! stretch d = L - L0 > 0, zero when slack.
    type, extends(line_attach_t) :: ligament_t
        real(wp) :: l1 = zero             !! linear coefficient [N/m]
        real(wp) :: l2 = zero             !! nonlinear coefficient [N/m^n]
        real(wp) :: n = 2.0_wp            !! exponent
    end type ligament_t

    !> Muscle, tension only: the paper's two-parameter viscoelastic element
    !! (eq 11), F = max(0, m1 d + m2 d' + a(t) Fmax), d = L - L0, with an
    !! optional activation table a(t) (beyond the paper); or a Hill-type
    !! muscle (hn_muscle) driven by an activation history.
    type, extends(line_attach_t) :: muscle_t
        integer :: law = muscle_passive   !! muscle_passive (eq 11) or muscle_hill
        real(wp) :: m1 = zero             !! eq 11 stiffness [N/m]
        real(wp) :: m2 = zero             !! eq 11 damping [N s/m]
        real(wp) :: fmax = zero           !! eq 11 force at full activation [N]
        integer :: activation = 0         !! eq 11: model table of a(t); 0 = passive
        type(hill_t) :: hill              !! Hill-type law parameters
        integer :: history = 0            !! Hill: model activation history; 0 = none (a = 0)
        integer :: nvia = 0               !! via points between the two ends, in path order
        integer :: via_body(max_via) = 0  !! their bodies (0 = inertial frame)
        real(wp) :: via_point(3, max_via) = zero   !! their positions in the body frames, from the mass centre [m]
    end type muscle_t

contains

    !> Ligament tension (eq 10) at length L.
    elemental real(wp) function ligament_tension(g, length) result(t)
        type(ligament_t), intent(in) :: g    !! the ligament
        real(wp), intent(in) :: length       !! current length [m]
        real(wp) :: d
        d = length - g%length0
        if (d > zero) then
            t = g%l1*d + g%l2*d**g%n
        else
            t = zero
        end if
    end function ligament_tension

    !> Elastic energy stored in a ligament at length L.
    elemental real(wp) function ligament_energy(g, length) result(u)
        type(ligament_t), intent(in) :: g    !! the ligament
        real(wp), intent(in) :: length       !! current length [m]
        real(wp) :: d
        d = length - g%length0
        if (d > zero) then
            u = 0.5_wp*g%l1*d**2 + g%l2*d**(g%n + one)/(g%n + one)
        else
            u = zero     ! slack: no power function evaluated (every evaluation computes the energy)
        end if
    end function ligament_energy

    !> Muscle tension (tension only) at length L, rate L' and activation a.
    !! L is the length of the muscle's path through its via points.
    elemental real(wp) function muscle_tension(m, length, rate, act) result(t)
        type(muscle_t), intent(in) :: m      !! the muscle
        real(wp), intent(in) :: length       !! current length [m]
        real(wp), intent(in) :: rate         !! lengthening rate [m/s]
        real(wp), intent(in) :: act          !! activation a(t) in [0, 1]
        t = max(zero, muscle_law_value(m, length, rate, act))
    end function muscle_tension

    !> The muscle's law before the tension-only clip: m1 d + m2 d' + a Fmax
    !! (eq 11) or the Hill force; the muscle pulls while it is positive.
    elemental real(wp) function muscle_law_value(m, length, rate, act) result(f)
        type(muscle_t), intent(in) :: m      !! the muscle
        real(wp), intent(in) :: length       !! current length [m]
        real(wp), intent(in) :: rate         !! lengthening rate [m/s]
        real(wp), intent(in) :: act          !! activation a(t) in [0, 1]
        if (m%law == muscle_hill) then
            f = hill_force(m%hill, length - m%length0, rate, act)
        else
            f = m%m1*(length - m%length0) + m%m2*rate + act*m%fmax
        end if
    end function muscle_law_value

    !> Spring-damper tension k (L - L0) + c L'.
    elemental real(wp) function spring_tension(s, length, rate) result(t)
        type(spring_t), intent(in) :: s      !! the spring
        real(wp), intent(in) :: length       !! current length [m]
        real(wp), intent(in) :: rate         !! lengthening rate [m/s]
        t = s%stiffness*(length - s%length0) + s%damping*rate
    end function spring_tension

    !> Elastic energy k (L - L0)^2 / 2 of a spring.
    elemental real(wp) function spring_energy(s, length) result(u)
        type(spring_t), intent(in) :: s      !! the spring
        real(wp), intent(in) :: length       !! current length [m]
        u = 0.5_wp*s%stiffness*(length - s%length0)**2
    end function spring_energy

    !> Position and velocity (R) of a point fixed in body k at body-frame
    !! offset c from the mass centre (k = 0: c is a point of R).
    pure subroutine attachment_point(kin, k, c, p, v)
        type(kinematics_t), intent(in) :: kin  !! kinematics of the tree
        integer, intent(in) :: k               !! body (0: inertial frame)
        real(wp), intent(in) :: c(3)           !! point in the body frame [m]
        real(wp), intent(out) :: p(3)          !! position in R [m]
        real(wp), intent(out) :: v(3)          !! velocity in R [m/s]
        real(wp) :: d(3), w(3)
        if (k == 0) then
            p = c; v = zero
        else
            d = kin%s(:, 1, k)*c(1) + kin%s(:, 2, k)*c(2) + kin%s(:, 3, k)*c(3)   ! S c, without a library matmul
            p = kin%r(:, k) + d
            w = kin%omega(:, k)
            ! v + omega x d written out: called for every end of every line element
            v(1) = kin%v(1, k) + (w(2)*d(3) - w(3)*d(2))
            v(2) = kin%v(2, k) + (w(3)*d(1) - w(1)*d(3))
            v(3) = kin%v(3, k) + (w(1)*d(2) - w(2)*d(1))
        end if
    end subroutine attachment_point

    !> Geometry of the line from point ca on body ka to point cb on body kb.
    pure subroutine line_geometry(kin, ka, ca, kb, cb, g)
        type(kinematics_t), intent(in) :: kin  !! kinematics of the tree
        integer, intent(in) :: ka              !! body of end a
        real(wp), intent(in) :: ca(3)          !! point a in body ka's frame [m]
        integer, intent(in) :: kb              !! body of end b
        real(wp), intent(in) :: cb(3)          !! point b in body kb's frame [m]
        type(line_geometry_t), intent(out) :: g  !! ends, unit vector a to b, length and its rate
        real(wp) :: pa(3), va(3), pb(3), vb(3)
        call attachment_point(kin, ka, ca, pa, va)
        call attachment_point(kin, kb, cb, pb, vb)
        call line_between(pa, va, pb, vb, g)
    end subroutine line_geometry

    !> Geometry of the line from point a to point b given their positions
    !! and velocities in R.
    pure subroutine line_between(pa, va, pb, vb, g)
        real(wp), intent(in) :: pa(3), va(3)     !! position [m] and velocity [m/s] of end a
        real(wp), intent(in) :: pb(3), vb(3)     !! position [m] and velocity [m/s] of end b
        type(line_geometry_t), intent(out) :: g  !! ends, unit vector a to b, length and its rate
        real(wp) :: d(3)
        g%pa = pa
        g%pb = pb
        d = pb - pa
        g%length = norm3(d)
        if (g%length > zero) then
            g%unit = d/g%length
        else
            g%unit = zero
        end if
        g%rate = dot_product(g%unit, vb - va)
    end subroutine line_between

    !> Geometry of every element of a list of line elements.
    pure subroutine line_geometries(kin, at, g)
        type(kinematics_t), intent(in) :: kin        !! kinematics of the tree
        class(line_attach_t), intent(in) :: at(:)    !! the elements (any kind)
        type(line_geometry_t), intent(out) :: g(:)   !! (size(at)) their geometry
        integer :: e
        do e = 1, size(at)
            call line_geometry(kin, at(e)%body_a, at(e)%point_a, at(e)%body_b, at(e)%point_b, g(e))
        end do
    end subroutine line_geometries

    !> Apply a tension (positive pulls the ends together) along the line.
    pure subroutine apply_line_tension(loads, kin, ka, kb, g, tension)
        type(body_loads_t), intent(inout) :: loads !! body loads, the tension's added
        type(kinematics_t), intent(in) :: kin  !! kinematics of the tree
        integer, intent(in) :: ka                !! body of end a (0: inertial frame)
        integer, intent(in) :: kb                !! body of end b (0: inertial frame)
        type(line_geometry_t), intent(in) :: g !! the line's geometry
        real(wp), intent(in) :: tension        !! [N]
        if (tension == zero) return             ! a slack element adds nothing
        if (ka > 0) call add_point_force(loads, ka, kin%r(:, ka), g%pa, tension*g%unit)
        if (kb > 0) call add_point_force(loads, kb, kin%r(:, kb), g%pb, -tension*g%unit)
    end subroutine apply_line_tension

    !> Apply the tensions of a list of line elements to their bodies.
    pure subroutine apply_line_tensions(loads, kin, at, g, tension)
        type(body_loads_t), intent(inout) :: loads !! body loads, the tensions added
        type(kinematics_t), intent(in) :: kin        !! kinematics of the tree
        class(line_attach_t), intent(in) :: at(:)    !! the elements (any kind)
        type(line_geometry_t), intent(in) :: g(:)    !! their geometry
        real(wp), intent(in) :: tension(:)           !! their tensions [N]
        integer :: e
        do e = 1, size(at)
            call apply_line_tension(loads, kin, at(e)%body_a, at(e)%body_b, g(e), tension(e))
        end do
    end subroutine apply_line_tensions

    !> Free lengths not given explicitly (negative) become the lengths in
    !! the configuration of `kin` (the neutral one); a muscle's is the
    !! length of its path through its via points.
    pure subroutine set_neutral_lengths(kin, at)
        type(kinematics_t), intent(in) :: kin        !! kinematics in the neutral configuration
        class(line_attach_t), intent(inout) :: at(:) !! the elements (any kind)
        type(line_geometry_t) :: g(size(at)), seg(max_via + 1, size(at))
        integer :: e
        select type (at)
        type is (muscle_t)
            call muscle_geometries(kin, at, g, seg)
        class default
            call line_geometries(kin, at, g)
        end select
        do e = 1, size(at)
            if (at(e)%length0 < zero) at(e)%length0 = g(e)%length
        end do
        select type (at)
        type is (muscle_t)
            at%hill%l0 = at%length0      ! the rest length of the short-range stiffness k = q F / L0
        end select
    end subroutine set_neutral_lengths

    !> The points of any line element's path in order: a muscle's through its
    !! via points (muscle_path_points), every other kind's its two ends.
    pure subroutine path_points(a, bodies, points, npt)
        class(line_attach_t), intent(in) :: a          !! the element
        integer, intent(out) :: bodies(max_via + 2)    !! bodies of the points (0 = inertial frame)
        real(wp), intent(out) :: points(3, max_via + 2) !! body-frame positions from the mass centre [m]
        integer, intent(out) :: npt                    !! number of points
        select type (a)
        type is (muscle_t)
            call muscle_path_points(a, bodies, points, npt)
        class default
            npt = 2
            bodies = 0
            points = zero
            bodies(1:2) = [a%body_a, a%body_b]
            points(:, 1) = a%point_a
            points(:, 2) = a%point_b
        end select
    end subroutine path_points

    !> The points of a muscle's path in order (origin, via points,
    !! insertion): their bodies and body-frame positions.
    pure subroutine muscle_path_points(m, bodies, points, npt)
        type(muscle_t), intent(in) :: m                !! the muscle
        integer, intent(out) :: bodies(max_via + 2)    !! bodies of the points (0 = inertial frame)
        real(wp), intent(out) :: points(3, max_via + 2) !! body-frame positions from the mass centre [m]
        integer, intent(out) :: npt                    !! number of points, nvia + 2
        npt = m%nvia + 2
        bodies = 0
        points = zero
        bodies(1) = m%body_a
        points(:, 1) = m%point_a
        bodies(2:npt - 1) = m%via_body(1:m%nvia)
        points(:, 2:npt - 1) = m%via_point(:, 1:m%nvia)
        bodies(npt) = m%body_b
        points(:, npt) = m%point_b
    end subroutine muscle_path_points

    !> Geometry of a muscle's path: length and lengthening rate summed over
    !! its segments; pa, pb the two ends; unit the direction of the first
    !! segment. `seg` receives the geometry of each segment. Each point of
    !! the path is placed once (a via point ends one segment and starts the next).
    pure subroutine muscle_geometry(kin, m, g, seg)
        type(kinematics_t), intent(in) :: kin  !! kinematics of the tree
        type(muscle_t), intent(in) :: m        !! the muscle
        type(line_geometry_t), intent(out) :: g  !! the whole path: ends, first direction, length and its rate
        type(line_geometry_t), intent(inout) :: seg(max_via + 1)   !! its segments in path order (nvia + 1 set, the rest left)
        integer :: bodies(max_via + 2), npt, k
        real(wp) :: points(3, max_via + 2), p(3, max_via + 2), v(3, max_via + 2)
        call muscle_path_points(m, bodies, points, npt)
        do k = 1, npt
            call attachment_point(kin, bodies(k), points(:, k), p(:, k), v(:, k))
        end do
        do k = 1, npt - 1
            call line_between(p(:, k), v(:, k), p(:, k + 1), v(:, k + 1), seg(k))
            g%length = g%length + seg(k)%length
            g%rate = g%rate + seg(k)%rate
        end do
        g%pa = seg(1)%pa
        g%unit = seg(1)%unit
        g%pb = seg(npt - 1)%pb
    end subroutine muscle_geometry

    !> Path geometry of every muscle of a list, and of each path's segments
    !! (inout: the unused segment slots are not cleared on every call).
    pure subroutine muscle_geometries(kin, muscles, g, seg, mirror)
        type(kinematics_t), intent(in) :: kin        !! kinematics of the tree
        type(muscle_t), intent(in) :: muscles(:)     !! the muscles
        type(line_geometry_t), intent(out) :: g(:)   !! (size(muscles)) their path geometry
        type(line_geometry_t), intent(inout), contiguous :: seg(:, :)  !! (max_via + 1, size(muscles)) their segments'
                                                                        !! geometry (nvia + 1 set per muscle, the rest left)
        integer, intent(in), optional :: mirror(:)   !! mirror_muscles: in a sagittal state an image is its pair's mirrored
        integer :: e, i, k
        logical :: sym
        sym = .false.
        if (present(mirror)) sym = any(mirror > 0)
        if (sym) sym = sagittal_state(kin)
        do e = 1, size(muscles)
            i = 0
            if (sym) i = mirror(e)
            if (i == 0) then
                call muscle_geometry(kin, muscles(e), g(e), seg(:, e))
            else
                g(e) = image(g(i))
                do k = 1, muscles(e)%nvia + 1
                    seg(k, e) = image(seg(k, i))
                end do
            end if
        end do
    contains
        pure type(line_geometry_t) function image(a)
            type(line_geometry_t), intent(in) :: a
            image = a
            image%pa(2) = -a%pa(2)
            image%pb(2) = -a%pb(2)
            image%unit(2) = -a%unit(2)
        end function image
    end subroutine muscle_geometries

    !> Mirror pairs of a list of muscles: mirror(e) = i < e when muscle e
    !! is the exact image of muscle i in the sagittal (xz) plane -- the
    !! same bodies, law, parameters and rest length, every point's y
    !! negated -- else 0 (their activations may differ: who uses the pair
    !! compares them). Each muscle is the image of one other at most.
    pure function mirror_muscles(muscles) result(mirror)
        type(muscle_t), intent(in) :: muscles(:)   !! the muscles (rest lengths set)
        integer :: mirror(size(muscles))
        integer :: e, i
        mirror = 0
        do e = 1, size(muscles)
            do i = 1, e - 1
                if (mirror(i) /= 0 .or. any(mirror == i)) cycle
                if (mirror_pair(muscles(i), muscles(e))) then
                    mirror(e) = i
                    exit
                end if
            end do
        end do
    end function mirror_muscles

    !> Whether muscle b is the exact image of muscle a in the xz plane.
    pure logical function mirror_pair(a, b)
        type(muscle_t), intent(in) :: a, b
        integer :: k
        mirror_pair = a%body_a == b%body_a .and. a%body_b == b%body_b .and. a%law == b%law .and. a%nvia == b%nvia .and. &
                      a%m1 == b%m1 .and. a%m2 == b%m2 .and. a%fmax == b%fmax .and. a%length0 == b%length0 .and. &
                      all(transfer(a%hill, [zero]) == transfer(b%hill, [zero])) .and. &
                      mirrored(a%point_a, b%point_a) .and. mirrored(a%point_b, b%point_b)
        do k = 1, a%nvia
            if (.not. mirror_pair) return
            mirror_pair = a%via_body(k) == b%via_body(k) .and. mirrored(a%via_point(:, k), b%via_point(:, k))
        end do
    contains
        pure logical function mirrored(p, q)
            real(wp), intent(in) :: p(3), q(3)
            mirrored = p(1) == q(1) .and. p(2) == -q(2) .and. p(3) == q(3)
        end function mirrored
    end function mirror_pair

    !> The tensions of a list of muscles; with mirror (mirror_muscles), an
    !! image whose length, rate and activation are its pair's takes its
    !! pair's tension (the same law and parameters give the same value).
    pure subroutine muscle_tensions(muscles, g, act, tension, mirror)
        type(muscle_t), intent(in) :: muscles(:)     !! the muscles
        type(line_geometry_t), intent(in) :: g(:)    !! (size(muscles)) their path geometry
        real(wp), intent(in) :: act(:)               !! (size(muscles)) their activations
        real(wp), intent(out) :: tension(:)          !! (size(muscles)) their tensions [N]
        integer, intent(in), optional :: mirror(:)   !! (size(muscles)) each image's pair, else 0
        integer :: e, i
        do e = 1, size(muscles)
            i = 0
            if (present(mirror)) i = mirror(e)
            if (i > 0) then
                if (g(e)%length == g(i)%length .and. g(e)%rate == g(i)%rate .and. act(e) == act(i)) then
                    tension(e) = tension(i)
                    cycle
                end if
            end if
            tension(e) = muscle_tension(muscles(e), g(e)%length, g(e)%rate, act(e))
        end do
    end subroutine muscle_tensions

    !> Whether the state of kin is exactly its own image in the xz plane:
    !! every body on the plane (y = 0, no y velocity), turned about y
    !! only (no x or z angular velocity). Then the image of a point has
    !! the image of its position and velocity, to the last bit.
    pure logical function sagittal_state(kin)
        type(kinematics_t), intent(in) :: kin   !! kinematics of the tree
        integer :: k
        sagittal_state = .false.
        do k = 1, size(kin%r, 2)
            if (kin%r(2, k) /= zero .or. kin%v(2, k) /= zero .or. kin%omega(1, k) /= zero .or. &
                kin%omega(3, k) /= zero) return
            if (kin%s(1, 2, k) /= zero .or. kin%s(2, 1, k) /= zero .or. kin%s(2, 3, k) /= zero .or. &
                kin%s(3, 2, k) /= zero) return
        end do
        sagittal_state = .true.
    end function sagittal_state

    !> Apply the muscles' tensions along their paths: on every segment the
    !! tension pulls its two points together (at a via point the two
    !! segments' pulls add up).
    pure subroutine apply_muscle_tensions(loads, kin, muscles, seg, tension)
        type(body_loads_t), intent(inout) :: loads !! body loads, the tensions added
        type(kinematics_t), intent(in) :: kin        !! kinematics of the tree
        type(muscle_t), intent(in) :: muscles(:)     !! the muscles
        type(line_geometry_t), intent(in) :: seg(:, :)   !! (max_via + 1, size(muscles)) their segments (muscle_geometries)
        real(wp), intent(in) :: tension(:)           !! their tensions [N]
        integer :: e, k, bodies(max_via + 2), npt
        real(wp) :: points(3, max_via + 2)
        do e = 1, size(muscles)
            if (tension(e) == zero) cycle
            call muscle_path_points(muscles(e), bodies, points, npt)
            do k = 1, npt - 1
                call apply_line_tension(loads, kin, bodies(k), bodies(k + 1), seg(k, e), tension(e))
            end do
        end do
    end subroutine apply_muscle_tensions

end module hn_line_elements
