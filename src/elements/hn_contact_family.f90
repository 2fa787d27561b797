!> The CONTACTS family: an ellipsoid on a body against a plane fixed in R
!! or on a body (a seat back, a head restraint, a sled floor), the law of
!! hn_contact_geometry behind the element-family interface. The force acts
!! at the contact point (the ellipsoid's support point), normal force and
!! friction on the ellipsoid's body, the reaction on the plane's. Outputs
!! per contact: normal force [N], friction force [N], penetration [mm,
!! as the channels' lengths] (negative: the gap), contact point in R [m]. The family reads its
!! CONTACT cards; a surface that starts inside its plane in the neutral
!! configuration is refused unless the card asks to offset the plane.
module hn_contact_family
    use hn_kinds, only: wp, zero, one
    use hn_deck_reader, only: deck_reader_t
    use hn_element_cards, only: card_context_t, body_ref, table_ref, map_ends, big_length, big_modulus
    use hn_kinematics, only: kinematics_t, kinematics_allocate, body_kinematics
    use hn_loads, only: body_loads_t, add_force_pair
    use hn_tree, only: body_tree_t
    use hn_tables, only: table_t
    use hn_rotation, only: cross
    use hn_contact_geometry, only: contact_t, contact_state_t, contact_geometry, normal_force, friction_force, &
                                   table_integral
    use hn_element_family, only: element_family_t, family_work_t, family_channel_t, element_table_t, table_data_t, &
                                 max_family_items, item_len, warning_len, check_point, add_line_tangent, spatial_row, &
                                 fd_rel, fd_abs_length
    use hn_family_registration, only: family_registration_t
    use hn_element_cards, only: family_card_t, unique_element
    use hn_element_family, only: family_slot_t, item_channels
    use hn_element_family, only: family_energy_t, tangent_work_t
    implicit none
    private

    public :: contact_family_t, contact_t
    public :: contact_registration

    integer, parameter :: ncomp_contact = 6   !! its outputs: N, friction, penetration, contact point (3)

    !> The contacts of a model and their force-penetration tables.
    type, extends(element_family_t) :: contact_family_t
        type(contact_t), allocatable :: items(:)
        type(table_t), allocatable :: tables(:)   !! loading and unloading tables (force [N] against penetration [m])
        integer :: nread = 0   !! contacts read from the deck so far (items holds room for every card until end_cards)
    contains
        procedure :: read_card => contact_read_card
        procedure :: end_cards => contact_end_cards
        procedure :: count => contact_count
        procedure :: ncomp => contact_ncomp
        procedure :: set_neutral => contact_neutral
        procedure :: add_loads => contact_loads
        procedure :: add_tangent => contact_tangent
        procedure :: switch_count => contact_count
        procedure :: switching => contact_switching
        procedure :: channels => contact_channels
        procedure :: result_table => contact_table
        procedure :: plausibility => contact_plausibility
        procedure :: scale_items => contact_items
        procedure :: scale => contact_scale
        procedure :: stiffen => contact_stiffen
    end type contact_family_t

contains

    !> Number of contacts (and of switching functions: one penetration each).
    pure integer function contact_count(this) result(n)
        class(contact_family_t), intent(in) :: this   !! the family
        n = 0
        if (allocated(this%items)) n = size(this%items)
    end function contact_count

    !> Output rows per contact: normal force, friction force, penetration, contact point.
    pure integer function contact_ncomp(this) result(n)
        class(contact_family_t), intent(in) :: this   !! the family
        n = ncomp_contact
    end function contact_ncomp

    !> Nothing to measure in the neutral configuration.
    pure subroutine contact_neutral(this, kin)
        class(contact_family_t), intent(inout) :: this   !! the family (unchanged)
        type(kinematics_t), intent(in) :: kin            !! kinematics of the neutral configuration (unused)
    end subroutine contact_neutral

    !> Forces of every contact at its contact point: N n + friction on the
    !! ellipsoid's body, the reaction on the plane's; stored energy (the
    !! loading curve's integral) and dissipated power (the rest of the work).
    pure subroutine contact_loads(this, t, kin, x, xd, loads, out, work, energy)
        class(contact_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at (x, xd)
        real(wp), intent(in) :: x(:)                  !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)                 !! their rates [m/s, rad/s]
        type(body_loads_t), intent(inout) :: loads    !! loads, the contacts' added
        real(wp), intent(inout) :: out(:, :)          !! (6, nc) N [N], friction [N], penetration [m], point (3) [m]
        type(family_work_t), intent(inout) :: work    !! scratch (unused)
        type(family_energy_t), intent(inout) :: energy !! energy stored, power dissipated and absorbed, the family's added
        type(contact_state_t) :: g
        real(wp) :: fn, fl, ft(3), rp(3)
        integer :: e
        do e = 1, size(this%items)
            associate (c => this%items(e))
                call contact_geometry(kin, c, g)
                out(:, e) = [zero, zero, 1000*g%depth, g%point]
                if (g%depth <= zero) cycle
                call normal_force(c, this%tables, g%depth, g%rate, fn, fl)
                ft = friction_force(c, fn, g%vt)
                out(1:2, e) = [fn, norm2(ft)]
                rp = zero
                if (c%plane_body > 0) rp = kin%r(:, c%plane_body)
                call add_force_pair(loads, c%plane_body, rp, c%body, kin%r(:, c%body), g%point, fn*g%normal + ft, &
                                    [zero, zero, zero])
                energy%u_elastic = energy%u_elastic + table_integral(this%tables(c%load), g%depth)
                energy%p_diss = energy%p_diss + (fn - fl)*g%rate - dot_product(ft, g%vt)
            end associate
        end do
    end subroutine contact_loads

    !> The row b_j = d(u . v_rel)/dxdot_j of the velocity of body kb's
    !! material point p relative to body ka's, along u: b_j = +-sj_j . phi
    !! with the spatial force phi = ((p - origin) x u; u) (+ on kb's chain,
    !! - on ka's).
    pure subroutine contact_row(tree, kin, ka, kb, p, u, cols, sgn, b)
        type(body_tree_t), intent(in) :: tree        !! the body tree
        type(kinematics_t), intent(in) :: kin        !! kinematics: joint columns filled
        integer, intent(in) :: ka                    !! the plane's body (0 = R)
        integer, intent(in) :: kb                    !! the ellipsoid's body
        real(wp), intent(in) :: p(3)                 !! the contact point in R [m]
        real(wp), intent(in) :: u(3)                 !! the direction in R
        integer, intent(out) :: cols(:)              !! scratch
        integer, intent(out) :: sgn(:)               !! scratch
        real(wp), intent(out) :: b(:)                !! (n) the row
        call spatial_row(tree, kin, ka, kb, [cross(p - kin%origin, u), u], cols, sgn, b)
    end subroutine contact_row

    !> K += (dN/dd) b b^T and C += (dN/dd') b b^T with b = dd'/dxdot (the
    !! normal law; central differences of the tables in d), and the
    !! friction's damping C += (mu N / max(|v_t|, v_s)) b_t b_t^T along the
    !! tangent directions it resists (both below v_s, the one across the
    !! slip beyond it).
    pure subroutine contact_tangent(this, tree, kin, t, x, xd, kgen, cgen, tw)
        class(contact_family_t), intent(in) :: this   !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree
        type(kinematics_t), intent(in) :: kin         !! kinematics: joint columns filled
        real(wp), intent(in) :: t                     !! time [s]
        real(wp), intent(in) :: x(:)                  !! active coordinates
        real(wp), intent(in) :: xd(:)                 !! their rates
        real(wp), intent(inout) :: kgen(:, :)         !! generalized stiffness, the contacts' added
        real(wp), intent(inout) :: cgen(:, :)         !! generalized damping, the contacts' added
        type(tangent_work_t), intent(inout) :: tw     !! scratch sized for the coordinates
        type(contact_state_t) :: g
        real(wp) :: fn, fl, fp, fm, dl, kl, cl, s, cf, t1(3), t2(3)
        integer :: e
        do e = 1, size(this%items)
            associate (c => this%items(e))
                call contact_geometry(kin, c, g)
                if (g%depth <= zero) cycle
                call normal_force(c, this%tables, g%depth, g%rate, fn, fl)
                dl = max(fd_rel*g%depth, fd_abs_length)
                call normal_force(c, this%tables, g%depth + dl, g%rate, fp, fl)
                call normal_force(c, this%tables, max(g%depth - dl, zero), g%rate, fm, fl)
                kl = (fp - fm)/(g%depth + dl - max(g%depth - dl, zero))
                cl = merge(c%damping, zero, fn > zero)
                call contact_row(tree, kin, c%plane_body, c%body, g%point, -g%normal, tw%cols, tw%sgn, tw%b)
                call add_line_tangent(tw%b, kl, cl, kgen, cgen, tw%idx)
                if (c%mu <= zero .or. fn <= zero) cycle
                s = norm2(g%vt)
                if (s < c%v_slip) then
                    cf = c%mu*fn/c%v_slip
                    call tangent_pair(g%normal, t1, t2)
                    call contact_row(tree, kin, c%plane_body, c%body, g%point, t1, tw%cols, tw%sgn, tw%b)
                    call add_line_tangent(tw%b, zero, cf, kgen, cgen, tw%idx)
                    call contact_row(tree, kin, c%plane_body, c%body, g%point, t2, tw%cols, tw%sgn, tw%b)
                    call add_line_tangent(tw%b, zero, cf, kgen, cgen, tw%idx)
                else
                    cf = c%mu*fn/s
                    call contact_row(tree, kin, c%plane_body, c%body, g%point, cross(g%normal, g%vt/s), tw%cols, tw%sgn, tw%b)
                    call add_line_tangent(tw%b, zero, cf, kgen, cgen, tw%idx)
                end if
            end associate
        end do
    end subroutine contact_tangent

    !> Two unit vectors t1, t2 with (t1, t2, n) orthonormal.
    pure subroutine tangent_pair(n, t1, t2)
        real(wp), intent(in) :: n(3)      !! unit normal
        real(wp), intent(out) :: t1(3)    !! first tangent
        real(wp), intent(out) :: t2(3)    !! second tangent
        if (abs(n(1)) < 0.9_wp) then
            t1 = cross(n, [one, zero, zero])
        else
            t1 = cross(n, [zero, one, zero])
        end if
        t1 = t1/norm2(t1)
        t2 = cross(n, t1)
    end subroutine tangent_pair

    !> The penetration of every contact (its sign changes where it touches or leaves).
    pure subroutine contact_switching(this, t, kin, x, sw)
        class(contact_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at x
        real(wp), intent(in) :: x(:)                  !! active coordinates (unused)
        real(wp), intent(out) :: sw(:)                !! (count) penetration of each [m]
        type(contact_state_t) :: g
        integer :: e
        do e = 1, size(this%items)
            call contact_geometry(kin, this%items(e), g)
            sw(e) = g%depth
        end do
    end subroutine contact_switching

    !> NAME_N normal force, NAME_F friction force [N], NAME_D penetration [mm].
    pure function contact_channels(this, tree) result(c)
        class(contact_family_t), intent(in) :: this   !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree (unused)
        type(family_channel_t), allocatable :: c(:)
        integer :: e
        c = item_channels([(this%items(e)%name, e=1, size(this%items))], ['N', 'F', 'D'], ['N ', 'N ', 'mm'], &
                          [character(len=16) :: 'CONTACT NORMAL', 'CONTACT FRICTION', 'CONTACT DEPTH'], [1, 2, 3])
    end function contact_channels

    !> /model/elements/contacts: body a the plane's, b the ellipsoid's;
    !! points the plane's point and the ellipsoid's centre; the semi-axes and
    !! the plane normals.
    pure function contact_table(this) result(tab)
        class(contact_family_t), intent(in) :: this   !! the family
        type(element_table_t) :: tab
        integer :: e, n
        n = size(this%items)
        tab%group = 'contacts'
        tab%description = 'ellipsoid on body b against the plane through point a on body a'
        allocate (tab%name(n), tab%extra(2))
        tab%name = this%items%name
        tab%body = reshape([(this%items(e)%plane_body, this%items(e)%body, e=1, n)], [2, n])
        tab%point = reshape([(this%items(e)%point, this%items(e)%centre, e=1, n)], [3, 2, n])
        tab%extra(1) = table_data_t('semi_axes', 'm', 'semi-axes of the ellipsoid along body b''s axes', &
                                    r=[(this%items(e)%semi, e=1, n)], shape=[3, n])
        tab%extra(2) = table_data_t('normal', '1', 'unit normal of the plane in body a''s frame (to the free side)', &
                                    r=[(this%items(e)%normal, e=1, n)], shape=[3, n])
    end function contact_table

    !> Ellipsoid centres far outside their bodies.
    pure subroutine contact_plausibility(this, tree, warnings)
        class(contact_family_t), intent(in) :: this   !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, the contacts' added
        integer :: e
        do e = 1, size(this%items)
            call check_point(tree, this%items(e)%body, this%items(e)%centre, 'contact '//this%items(e)%name, warnings)
        end do
    end subroutine contact_plausibility

    !> K (the force tables), C (damping), MU (friction).
    pure subroutine contact_items(this, items)
        class(contact_family_t), intent(in) :: this   !! the family
        character(len=item_len), intent(out) :: items(max_family_items)   !! the properties
        items = ''
        items(1:3) = [character(len=item_len) :: 'K', 'C', 'MU']
    end subroutine contact_items

    !> Scale the force tables, the damping or the friction coefficient of every contact.
    pure subroutine contact_scale(this, item, factor)
        class(contact_family_t), intent(inout) :: this   !! the family
        character(len=*), intent(in) :: item             !! K, C or MU
        real(wp), intent(in) :: factor                   !! the factor
        select case (item)
        case ('K'); call contact_stiffen(this, factor)
        case ('C'); this%items%damping = factor*this%items%damping
        case ('MU'); this%items%mu = factor*this%items%mu
        end select
    end subroutine contact_scale

    !> STIFFEN: the forces of the loading and unloading tables.
    pure subroutine contact_stiffen(this, factor)
        class(contact_family_t), intent(inout) :: this   !! the family
        real(wp), intent(in) :: factor                   !! the factor
        integer :: k
        do k = 1, size(this%tables)
            this%tables(k)%y = factor*this%tables(k)%y
        end do
    end subroutine contact_stiffen

    !> A CONTACT card (docs/deck-format.md): name, the ellipsoid's body, the
    !! plane's body or R, loading and unloading tables, damping, friction
    !! coefficient; the ellipsoid (semi-axes, centre, slip velocity) on the
    !! first continuation card, the plane (point, normal, OFFSET) on the
    !! second. The penetration in the neutral configuration must not be
    !! positive, unless F7 of the second continuation card is OFFSET: the
    !! plane then moves along its normal until the ellipsoid touches it.
    subroutine contact_read_card(this, rd, ctx, i, key)
        class(contact_family_t), intent(inout) :: this   !! the family; out: the contact added
        type(deck_reader_t), intent(inout) :: rd         !! the deck: card images, located field access, the first error
        type(card_context_t), intent(inout) :: ctx       !! the deck's bodies and tables; out: ninternal counted
        integer, intent(in) :: i                         !! the card's first deck line
        character(len=*), intent(in) :: key              !! the card name (CONTACT)
        type(contact_t) :: c
        character(len=10) :: nm, opt
        real(wp) :: depth
        integer :: f, tl, tu
        if (ctx%needs_room(key, this%nread, size(this%items))) then
            deallocate (this%items)
            allocate (this%items(ctx%ncards(key)))
        end if
        call rd%name(i, 1, 'contact name', nm)
        c%name = nm
        c%body = body_ref(rd, i, 2, 'ellipsoid body', ctx%bnames, .false.)
        c%plane_body = body_ref(rd, i, 3, 'plane body', ctx%bnames, .true.)
        if (.not. rd%failed() .and. c%body == c%plane_body) &
            call rd%fail(rd%context(i, 3, 'plane body')//': found the ellipsoid''s body again; '// &
                         'expected another body or R')
        tl = table_ref(rd, i, 4, ctx%tabs)
        call force_table(rd, i, 4, 'loading table', ctx, tl)
        tu = 0
        if (.not. rd%failed() .and. .not. rd%is_blank(i, 5)) then
            tu = table_ref(rd, i, 5, ctx%tabs)
            call force_table(rd, i, 5, 'unloading table', ctx, tu)
        end if
        call rd%real(i, 6, 'damping', 'N s/m', c%damping, zero, big_modulus, default=zero)
        call rd%real(i, 7, 'friction coefficient', '-', c%mu, zero, 10.0_wp, default=zero)
        do f = 1, 3
            call rd%real(i + 1, f, 'semi-axis', 'm', c%semi(f), 1.0e-4_wp, big_length)
        end do
        do f = 1, 3
            call rd%real(i + 1, 3 + f, 'ellipsoid centre', 'm', c%centre(f), -big_length, big_length, default=zero)
        end do
        call rd%real(i + 1, 7, 'slip velocity', 'm/s', c%v_slip, 1.0e-6_wp, 10.0_wp, default=0.01_wp)
        do f = 1, 3
            call rd%real(i + 2, f, 'plane point', 'm', c%point(f), -big_length, big_length, default=zero)
        end do
        do f = 1, 3
            call rd%real(i + 2, 3 + f, 'plane normal', '-', c%normal(f), -big_modulus, big_modulus, default=zero)
        end do
        if (rd%failed()) return
        if (all(c%normal == zero)) then
            call rd%fail(rd%where(i + 2)//', columns 41-70 (CONTACT card continuation 2, fields F4-F6 ''plane '// &
                         'normal''): found a zero vector; expected the plane''s normal, pointing to the free side')
            return
        end if
        c%normal = c%normal/norm2(c%normal)
        call rd%name(i + 2, 7, 'initial penetration', opt, optional_blank=.true.)
        if (rd%failed()) return
        if (opt /= '' .and. opt /= 'OFFSET') then
            call rd%fail(rd%context(i + 2, 7, 'initial penetration')//': found "'//trim(opt)// &
                         '"; expected OFFSET or blank')
            return
        end if
        this%tables = [this%tables, ctx%tabs(tl)%tab]
        c%load = size(this%tables)
        if (tu > 0) then
            this%tables = [this%tables, ctx%tabs(tu)%tab]
            c%unload = size(this%tables)
        end if
        call map_ends(ctx%bmap, c%plane_body, c%point, c%body, c%centre, ctx%ninternal)
        if (c%body == c%plane_body) return     ! both on one merged body: dropped
        depth = neutral_depth(ctx%tree, c)
        if (depth > zero) then
            if (opt == 'OFFSET') then
                c%point = c%point - depth*c%normal
                call ctx%add_note('contact '//trim(c%name)//': plane offset to touch at the start')
            else
                call rd%fail(rd%where(i)//' (CONTACT card '//trim(c%name)//'): the ellipsoid starts '// &
                             trim(real_text(1000*depth))//' mm inside the plane in the neutral configuration; '// &
                             'expected a gap or contact, or OFFSET in F7 of continuation card 2')
                return
            end if
        end if
        this%nread = this%nread + 1
        this%items(this%nread) = c
    end subroutine contact_read_card

    !> A force-penetration table: forces not negative.
    subroutine force_table(rd, i, f, what, ctx, it)
        type(deck_reader_t), intent(inout) :: rd      !! the deck
        integer, intent(in) :: i                      !! the card's first deck line
        integer, intent(in) :: f                      !! the field naming the table
        character(len=*), intent(in) :: what          !! loading or unloading table
        type(card_context_t), intent(in) :: ctx       !! the deck's tables
        integer, intent(in) :: it                     !! the table
        if (rd%failed()) return
        if (any(ctx%tabs(it)%tab%y < zero)) &
            call rd%fail(rd%context(i, f, what)//': table '//trim(ctx%tabs(it)%name)// &
                         ' has a negative force; expected forces >= 0 [N] against penetration [m]')
    end subroutine force_table

    !> Penetration of contact c in the neutral configuration of the tree.
    pure real(wp) function neutral_depth(tree, c) result(depth)
        type(body_tree_t), intent(in) :: tree   !! the reduced tree
        type(contact_t), intent(in) :: c        !! the contact
        type(kinematics_t) :: kin
        type(contact_state_t) :: g
        real(wp) :: x(tree%ndof)
        integer :: j
        do j = 1, tree%ndof
            x(j) = tree%q_ref(tree%dof_local(j), tree%dof_body(j))
        end do
        call kinematics_allocate(tree, kin)
        call body_kinematics(tree, x, 0*x, kin)
        call contact_geometry(kin, c, g)
        depth = g%depth
    end function neutral_depth

    !> A real number in three significant digits.
    pure function real_text(v) result(s)
        real(wp), intent(in) :: v        !! the number
        character(len=:), allocatable :: s
        character(len=16) :: buf
        write (buf, '(g10.3)') v
        s = trim(adjustl(buf))
    end function real_text

    !> The contacts read: no room left over.
    subroutine contact_end_cards(this, rd, ctx)
        class(contact_family_t), intent(inout) :: this   !! the family; out: items trimmed to the contacts read
        type(deck_reader_t), intent(inout) :: rd         !! the deck (unused)
        type(card_context_t), intent(inout) :: ctx       !! the deck's cards (unused)
        this%items = this%items(1:this%nread)
    end subroutine contact_end_cards

    !> The registry's entry of the contacts: name CONTACTS, its card CONTACT (two
    !! continuation cards), and the family with no elements.
    pure function contact_registration() result(r)
        type(family_registration_t) :: r
        r = family_registration_t('CONTACTS', [family_card_t('CONTACT', 0, 2, unique=unique_element)], contact_empty)
    end function contact_registration

    !> A family of contacts with no elements (its arrays allocated with size 0, not
    !! taken from a zero-size array constructor, which gfortran copies into
    !! an unallocated component when the model is copied).
    pure subroutine contact_empty(slot)
        type(family_slot_t), intent(out) :: slot   !! the slot, holding the empty family
        type(contact_t), allocatable :: ct(:)
        type(table_t), allocatable :: tb(:)
        allocate (ct(0), tb(0)); allocate (slot%f, source=contact_family_t(items=ct, tables=tb))
    end subroutine contact_empty

end module hn_contact_family
