!> The FACETS family: the facet (zygapophyseal) joints of a motion segment,
!! each a compression-only contact between a point of the upper vertebra's
!! inferior articular process and the plane of the lower vertebra's
!! superior articular facet.
!!
!! Geometry. The facet's centre P and its unit normal n (to the free side,
!! towards the upper vertebra) are fixed in the lower body's frame; the
!! normal comes from two angles: the inclination theta of the facet plane
!! to the lower body's transverse (X-Y) plane, the normal tilted backward
!! from Z, and the angle phi by which the normal's horizontal part turns
!! from backward (-X) towards +Y:
!! n = (-sin(theta) cos(phi), sin(theta) sin(phi), cos(theta)).
!! The upper point p is fixed in the upper body's frame, placed in the
!! neutral configuration at P + g n (g the card's gap). The penetration is
!! d = -n . (p - P) (-g in the neutral configuration; d > 0: the cartilage
!! compressed), its rate d' = -n . v_rel with v_rel the velocity of the
!! upper body's material point at p relative to the lower body's there
!! (the exact derivative, n turning with the lower body).
!!
!! Law. N = max(0, k d^e + c d') for d > 0, zero when open: the force
!! never pulls. It acts along n on the upper body at p, the reaction on the
!! lower body at the same point, so the moment about each body's mass
!! centre is r x F with r from that mass centre to p (equal and opposite
!! about any common point). Stored energy k d^(e+1)/(e+1); the rest of the
!! work N d' is dissipated (damping, and the clipping of a pull to zero).
!! Tangent: K += (dN/dd) b b^T, C += c b b^T with b = dd'/dxdot (the
!! rotation of n under the force, N db/dx, is left out, as the contacts'
!! tangent does).
!!
!! Outputs per facet: normal force [N], penetration [mm, as the channels'
!! lengths] (negative: the gap), the point p in R [m].
module hn_facet_family
    use hn_kinds, only: wp, zero, one, deg
    use hn_deck_reader, only: deck_reader_t
    use hn_element_cards, only: card_context_t, body_ref, map_ends, big_length, big_modulus, family_card_t, &
                                unique_element
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t, add_force_pair
    use hn_tree, only: body_tree_t
    use hn_rotation, only: cross
    use hn_element_family, only: element_family_t, family_work_t, family_channel_t, element_table_t, table_data_t, &
                                 max_family_items, item_len, warning_len, check_point, add_line_tangent, spatial_row, &
                                 family_slot_t, item_channels
    use hn_family_registration, only: family_registration_t
    use hn_element_family, only: family_energy_t, tangent_work_t
    implicit none
    private

    public :: facet_t, facet_state_t, facet_family_t, facet_geometry, facet_force, facet_normal
    public :: facet_registration

    integer, parameter :: ncomp_facet = 5   !! its outputs: N, penetration, the point p (3)

    !> One facet joint: the upper body's point against the lower body's facet plane.
    type :: facet_t
        character(len=12) :: name = ''
        integer :: lower = 1                        !! body of the facet plane (the lower vertebra)
        integer :: upper = 2                        !! body of the point (the upper vertebra)
        real(wp) :: centre(3) = zero                !! facet centre P in the lower body's frame, from its mass centre [m]
        real(wp) :: normal(3) = [zero, zero, one]   !! unit normal n in the lower body's frame (to the upper vertebra)
        real(wp) :: point(3) = zero                 !! the point p in the upper body's frame (set_neutral) [m]
        real(wp) :: gap = zero                      !! gap g in the neutral configuration [m]
        real(wp) :: k = zero                        !! stiffness k [N/m^e]
        real(wp) :: expo = one                      !! exponent e of the law (1 to 4)
        real(wp) :: damping = zero                  !! damping c [N s/m]
    end type facet_t

    !> Where a facet is at one instant.
    type :: facet_state_t
        real(wp) :: depth = zero       !! penetration d [m] (negative: the gap)
        real(wp) :: rate = zero        !! its rate d' [m/s]
        real(wp) :: point(3) = zero    !! the point p in R [m]
        real(wp) :: normal(3) = zero   !! the normal n in R
    end type facet_state_t

    !> The facets of a model.
    type, extends(element_family_t) :: facet_family_t
        type(facet_t), allocatable :: items(:)
        integer :: nread = 0   !! facets read from the deck so far (items holds room for every card until end_cards)
    contains
        procedure :: read_card => facet_read_card
        procedure :: end_cards => facet_end_cards
        procedure :: count => facet_count
        procedure :: ncomp => facet_ncomp
        procedure :: set_neutral => facet_neutral
        procedure :: add_loads => facet_loads
        procedure :: add_tangent => facet_tangent
        procedure :: switch_count => facet_count
        procedure :: switching => facet_switching
        procedure :: channels => facet_channels
        procedure :: result_table => facet_table
        procedure :: plausibility => facet_plausibility
        procedure :: scale_items => facet_items
        procedure :: scale => facet_scale
        procedure :: stiffen => facet_stiffen
    end type facet_family_t

contains

    !> The unit normal of a facet plane from its inclination to the
    !! transverse plane and its turn about Z (module header).
    pure function facet_normal(theta, phi) result(n)
        real(wp), intent(in) :: theta   !! inclination of the plane to the transverse plane [rad]
        real(wp), intent(in) :: phi     !! turn of the normal's horizontal part from -X towards +Y [rad]
        real(wp) :: n(3)
        n = [-sin(theta)*cos(phi), sin(theta)*sin(phi), cos(theta)]
    end function facet_normal

    !> The geometry of facet f at the kinematics kin.
    pure subroutine facet_geometry(kin, f, g)
        type(kinematics_t), intent(in) :: kin      !! kinematics of the tree (body level)
        type(facet_t), intent(in) :: f             !! the facet
        type(facet_state_t), intent(out) :: g      !! its geometry
        real(wp) :: pc(3), vrel(3)
        associate (sl => kin%s(:, :, f%lower), rl => kin%r(:, f%lower), ru => kin%r(:, f%upper))
            g%normal = matmul(sl, f%normal)
            pc = rl + matmul(sl, f%centre)
            g%point = ru + matmul(kin%s(:, :, f%upper), f%point)
            g%depth = -dot_product(g%normal, g%point - pc)
            vrel = kin%v(:, f%upper) + cross(kin%omega(:, f%upper), g%point - ru) &
                   - kin%v(:, f%lower) - cross(kin%omega(:, f%lower), g%point - rl)
            g%rate = -dot_product(g%normal, vrel)
        end associate
    end subroutine facet_geometry

    !> Normal force N [N] of facet f at penetration d [m] and rate dd [m/s],
    !! its elastic part k d^e [N] and its slopes dN/dd [N/m] and dN/dd' [N s/m]
    !! (all zero when open or when the damping would pull).
    pure subroutine facet_force(f, d, dd, force, elastic, kd, cd)
        type(facet_t), intent(in) :: f          !! the facet
        real(wp), intent(in) :: d               !! penetration [m]
        real(wp), intent(in) :: dd              !! its rate [m/s]
        real(wp), intent(out) :: force          !! normal force N [N]
        real(wp), intent(out) :: elastic        !! elastic force k d^e [N]
        real(wp), intent(out) :: kd             !! dN/dd [N/m]
        real(wp), intent(out) :: cd             !! dN/dd' [N s/m]
        force = zero; elastic = zero; kd = zero; cd = zero
        if (d <= zero) return
        elastic = f%k*d**f%expo
        force = elastic + f%damping*dd
        if (force <= zero) then
            force = zero
            return
        end if
        kd = f%expo*f%k*d**(f%expo - one)
        cd = f%damping
    end subroutine facet_force

    !> Number of facets (and of switching functions: one penetration each).
    pure integer function facet_count(this) result(n)
        class(facet_family_t), intent(in) :: this   !! the family
        n = 0
        if (allocated(this%items)) n = size(this%items)
    end function facet_count

    !> Output rows per facet: normal force, penetration, the point p.
    pure integer function facet_ncomp(this) result(n)
        class(facet_family_t), intent(in) :: this   !! the family
        n = ncomp_facet
    end function facet_ncomp

    !> The upper point of every facet: P + g n of the neutral configuration,
    !! in the upper body's frame.
    pure subroutine facet_neutral(this, kin)
        class(facet_family_t), intent(inout) :: this   !! the family; out: the upper points set
        type(kinematics_t), intent(in) :: kin          !! kinematics of the neutral configuration
        real(wp) :: p(3)
        integer :: e
        do e = 1, size(this%items)
            associate (f => this%items(e))
                p = kin%r(:, f%lower) + matmul(kin%s(:, :, f%lower), f%centre + f%gap*f%normal)
                f%point = matmul(p - kin%r(:, f%upper), kin%s(:, :, f%upper))
            end associate
        end do
    end subroutine facet_neutral

    !> Forces of every closed facet along its normal at the point p: on the
    !! upper body, the reaction on the lower; stored energy and dissipated power.
    pure subroutine facet_loads(this, t, kin, x, xd, loads, out, work, energy)
        class(facet_family_t), intent(in) :: this    !! the family
        real(wp), intent(in) :: t                    !! time [s]
        type(kinematics_t), intent(in) :: kin        !! kinematics at (x, xd)
        real(wp), intent(in) :: x(:)                 !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)                !! their rates [m/s, rad/s]
        type(body_loads_t), intent(inout) :: loads   !! loads, the facets' added
        real(wp), intent(inout) :: out(:, :)         !! (5, nf) N [N], penetration [mm], point (3) [m]
        type(family_work_t), intent(inout) :: work   !! scratch (unused)
        type(family_energy_t), intent(inout) :: energy !! energy stored, power dissipated and absorbed, the family's added
        type(facet_state_t) :: g
        real(wp) :: fn, fe, kd, cd
        integer :: e
        do e = 1, size(this%items)
            associate (f => this%items(e))
                call facet_geometry(kin, f, g)
                out(:, e) = [zero, 1000*g%depth, g%point]
                if (g%depth <= zero) cycle
                call facet_force(f, g%depth, g%rate, fn, fe, kd, cd)
                out(1, e) = fn
                energy%u_elastic = energy%u_elastic + f%k*g%depth**(f%expo + one)/(f%expo + one)
                energy%p_diss = energy%p_diss + (fn - fe)*g%rate
                if (fn <= zero) cycle
                call add_force_pair(loads, f%lower, kin%r(:, f%lower), f%upper, kin%r(:, f%upper), g%point, &
                                    fn*g%normal, [zero, zero, zero])
            end associate
        end do
    end subroutine facet_loads

    !> K += (dN/dd) b b^T and C += (dN/dd') b b^T with b = dd'/dxdot, the
    !! row of -n . v_rel (module header).
    pure subroutine facet_tangent(this, tree, kin, t, x, xd, kgen, cgen, tw)
        class(facet_family_t), intent(in) :: this   !! the family
        type(body_tree_t), intent(in) :: tree       !! the body tree
        type(kinematics_t), intent(in) :: kin       !! kinematics: joint columns filled
        real(wp), intent(in) :: t                   !! time [s]
        real(wp), intent(in) :: x(:)                !! active coordinates
        real(wp), intent(in) :: xd(:)               !! their rates
        real(wp), intent(inout) :: kgen(:, :)       !! generalized stiffness, the facets' added
        real(wp), intent(inout) :: cgen(:, :)       !! generalized damping, the facets' added
        type(tangent_work_t), intent(inout) :: tw   !! scratch sized for the coordinates
        type(facet_state_t) :: g
        real(wp) :: fn, fe, kd, cd
        integer :: e
        do e = 1, size(this%items)
            associate (f => this%items(e))
                call facet_geometry(kin, f, g)
                if (g%depth <= zero) cycle
                call facet_force(f, g%depth, g%rate, fn, fe, kd, cd)
                if (fn <= zero) cycle
                call spatial_row(tree, kin, f%lower, f%upper, [cross(g%point - kin%origin, -g%normal), -g%normal], &
                                 tw%cols, tw%sgn, tw%b)
                call add_line_tangent(tw%b, kd, cd, kgen, cgen, tw%idx)
            end associate
        end do
    end subroutine facet_tangent

    !> The penetration of every facet (its sign changes where it closes or opens).
    pure subroutine facet_switching(this, t, kin, x, sw)
        class(facet_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: t                   !! time [s]
        type(kinematics_t), intent(in) :: kin       !! kinematics at x
        real(wp), intent(in) :: x(:)                !! active coordinates (unused)
        real(wp), intent(out) :: sw(:)              !! (count) penetration of each [m]
        type(facet_state_t) :: g
        integer :: e
        do e = 1, size(this%items)
            call facet_geometry(kin, this%items(e), g)
            sw(e) = g%depth
        end do
    end subroutine facet_switching

    !> NAME_N normal force [N], NAME_D penetration [mm].
    pure function facet_channels(this, tree) result(c)
        class(facet_family_t), intent(in) :: this   !! the family
        type(body_tree_t), intent(in) :: tree       !! the body tree (unused)
        type(family_channel_t), allocatable :: c(:)
        integer :: e
        c = item_channels([(this%items(e)%name, e=1, size(this%items))], ['N', 'D'], ['N ', 'mm'], &
                          [character(len=16) :: 'FACET FORCE', 'FACET DEPTH'], [1, 2])
    end function facet_channels

    !> /model/elements/facets: body a the lower (the plane's), b the upper;
    !! points the facet centre and the upper point; the normals, the gaps
    !! and the laws.
    pure function facet_table(this) result(tab)
        class(facet_family_t), intent(in) :: this   !! the family
        type(element_table_t) :: tab
        integer :: e, n
        n = size(this%items)
        tab%group = 'facets'
        tab%description = 'facet joints: the point b on the upper body against the plane through a on the lower body'
        allocate (tab%name(n), tab%extra(3))
        tab%name = this%items%name
        tab%body = reshape([(this%items(e)%lower, this%items(e)%upper, e=1, n)], [2, n])
        tab%point = reshape([(this%items(e)%centre, this%items(e)%point, e=1, n)], [3, 2, n])
        tab%extra(1) = table_data_t('normal', '1', 'unit normal of the facet plane in body a''s frame (to body b)', &
                                    r=[(this%items(e)%normal, e=1, n)], shape=[3, n])
        tab%extra(2) = table_data_t('gap', 'm', 'gap in the neutral configuration', r=this%items%gap, shape=[n])
        tab%extra(3) = table_data_t('law', '-', 'k [N/m^e], exponent e, damping c [N s/m]', &
                                    r=[(this%items(e)%k, this%items(e)%expo, this%items(e)%damping, e=1, n)], &
                                    shape=[3, n])
    end function facet_table

    !> Facet centres far outside their lower bodies.
    pure subroutine facet_plausibility(this, tree, warnings)
        class(facet_family_t), intent(in) :: this   !! the family
        type(body_tree_t), intent(in) :: tree       !! the body tree
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, the facets' added
        integer :: e
        do e = 1, size(this%items)
            call check_point(tree, this%items(e)%lower, this%items(e)%centre, 'facet '//this%items(e)%name, warnings)
        end do
    end subroutine facet_plausibility

    !> K (the stiffness k), C (damping).
    pure subroutine facet_items(this, items)
        class(facet_family_t), intent(in) :: this   !! the family
        character(len=item_len), intent(out) :: items(max_family_items)   !! the properties
        items = ''
        items(1:2) = [character(len=item_len) :: 'K', 'C']
    end subroutine facet_items

    !> Scale the stiffness or the damping of every facet.
    pure subroutine facet_scale(this, item, factor)
        class(facet_family_t), intent(inout) :: this   !! the family
        character(len=*), intent(in) :: item           !! K or C
        real(wp), intent(in) :: factor                 !! the factor
        select case (item)
        case ('K'); call facet_stiffen(this, factor)
        case ('C'); this%items%damping = factor*this%items%damping
        end select
    end subroutine facet_scale

    !> STIFFEN: the stiffness k of every facet.
    pure subroutine facet_stiffen(this, factor)
        class(facet_family_t), intent(inout) :: this   !! the family
        real(wp), intent(in) :: factor                 !! the factor
        this%items%k = factor*this%items%k
    end subroutine facet_stiffen

    !> A FACET card (docs/deck-format.md): name, the lower and the upper
    !! body, stiffness, exponent, damping, gap; the facet centre in the lower
    !! body's frame and the plane's two angles on the continuation card.
    subroutine facet_read_card(this, rd, ctx, i, key)
        class(facet_family_t), intent(inout) :: this   !! the family; out: the facet added
        type(deck_reader_t), intent(inout) :: rd       !! the deck: card images, located field access, the first error
        type(card_context_t), intent(inout) :: ctx     !! the deck's bodies; out: ninternal counted
        integer, intent(in) :: i                       !! the card's first deck line
        character(len=*), intent(in) :: key            !! the card name (FACET)
        type(facet_t) :: f
        character(len=10) :: nm
        real(wp) :: theta, phi, dummy(3)
        integer :: c
        if (ctx%needs_room(key, this%nread, size(this%items))) then
            deallocate (this%items)
            allocate (this%items(ctx%ncards(key)))
        end if
        call rd%name(i, 1, 'facet name', nm)
        f%name = nm
        f%lower = body_ref(rd, i, 2, 'lower body', ctx%bnames, .false.)
        f%upper = body_ref(rd, i, 3, 'upper body', ctx%bnames, .false.)
        if (.not. rd%failed() .and. f%lower == f%upper) &
            call rd%fail(rd%context(i, 3, 'upper body')//': found the lower body again; expected another body')
        call rd%real(i, 4, 'stiffness k', 'N/m^e', f%k, zero, big_modulus)
        call rd%real(i, 5, 'exponent e', '-', f%expo, one, 4.0_wp, default=one)
        call rd%real(i, 6, 'damping', 'N s/m', f%damping, zero, big_modulus, default=zero)
        call rd%real(i, 7, 'gap', 'm', f%gap, zero, 0.01_wp, default=zero)
        do c = 1, 3
            call rd%real(i + 1, c, 'facet centre', 'm', f%centre(c), -big_length, big_length)
        end do
        call rd%real(i + 1, 4, 'inclination', 'deg', theta, -90.0_wp, 90.0_wp)
        call rd%real(i + 1, 5, 'turn of the normal', 'deg', phi, -180.0_wp, 180.0_wp, default=zero)
        if (rd%failed()) return
        f%normal = facet_normal(theta*deg, phi*deg)
        dummy = zero
        call map_ends(ctx%bmap, f%lower, f%centre, f%upper, dummy, ctx%ninternal)
        if (f%lower == f%upper) return     ! both on one merged body: dropped
        this%nread = this%nread + 1
        this%items(this%nread) = f
    end subroutine facet_read_card

    !> The facets read: no room left over.
    subroutine facet_end_cards(this, rd, ctx)
        class(facet_family_t), intent(inout) :: this   !! the family; out: items trimmed to the facets read
        type(deck_reader_t), intent(inout) :: rd       !! the deck (unused)
        type(card_context_t), intent(inout) :: ctx     !! the deck's cards (unused)
        this%items = this%items(1:this%nread)
    end subroutine facet_end_cards

    !> The registry's entry of the facets: name FACETS, its card FACET (one
    !! continuation card), and the family with no elements.
    pure function facet_registration() result(r)
        type(family_registration_t) :: r
        r = family_registration_t('FACETS', [family_card_t('FACET', 0, 1, unique=unique_element)], facet_empty)
    end function facet_registration

    !> A family of facets with no elements (its array allocated with size 0).
    pure subroutine facet_empty(slot)
        type(family_slot_t), intent(out) :: slot   !! the slot, holding the empty family
        type(facet_t), allocatable :: ft(:)
        allocate (ft(0)); allocate (slot%f, source=facet_family_t(items=ft))
    end subroutine facet_empty

end module hn_facet_family
