!> The DISCS family: Timoshenko discs between vertebral plates (eqs 1-9,
!! hn_discs), behind the element-family interface. Output per disc: the six
!! resultants (shear x, y, axial [N], bending x, y, torque [N m]). The
!! family reads its DISC cards (`disc_card`).
module hn_disc_family
    use hn_kinds, only: wp, zero, one, deg
    use hn_deck_reader, only: deck_reader_t
    use hn_element_cards, only: card_context_t, body_map_t, body_ref, distinct_bodies, map_ends, big_length, big_modulus
    use hn_rotation, only: cross
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t
    use hn_tree, only: body_tree_t
    use hn_discs, only: disc_t, apply_disc, disc_set_reference, disc_deformation, disc_resultants, inv_left_jacobian
    use hn_element_family, only: element_family_t, family_work_t, family_channel_t, element_table_t, table_data_t, &
                                 max_family_items, &
                                 item_len, warning_len, fd_rel, fd_abs_length, fd_abs_rate, path_columns, check_point, &
                                 check_range
    use hn_family_registration, only: family_registration_t
    use hn_element_cards, only: family_card_t, unique_element
    use hn_element_family, only: family_slot_t, item_channels
    use hn_element_family, only: family_energy_t, tangent_work_t
    implicit none
    private

    public :: disc_family_t, discs_of, disc_card
    public :: disc_registration

    real(wp), parameter :: ref_disc_axial = 5.0e5_wp      !! N/m (reference/parameters.md)
    real(wp), parameter :: ref_disc_bending = 20.0_wp     !! N m/rad

    !> The discs of a model.
    type, extends(element_family_t) :: disc_family_t
        type(disc_t), allocatable :: items(:)
        integer :: nread = 0   !! discs read from the deck so far (items holds room for every DISC card until end_cards)
    contains
        procedure :: read_card => disc_read_card
        procedure :: end_cards => disc_end_cards
        procedure :: count => disc_count
        procedure :: ncomp => disc_ncomp
        procedure :: set_neutral => disc_neutral
        procedure :: add_loads => disc_loads
        procedure :: add_tangent => disc_tangent
        procedure :: switch_count => disc_switch_count
        procedure :: switching => disc_switching
        procedure :: channels => disc_channels
        procedure :: result_table => disc_table
        procedure :: plausibility => disc_plausibility
        procedure :: scale_items => disc_items
        procedure :: scale => disc_scale
        procedure :: stiffen => disc_stiffen
        procedure :: prestrain => disc_prestrain
    end type disc_family_t

contains

    !> Number of discs.
    pure integer function disc_count(this) result(n)
        class(disc_family_t), intent(in) :: this   !! the family
        n = 0
        if (allocated(this%items)) n = size(this%items)
    end function disc_count

    !> Output rows per disc: the six resultants.
    pure integer function disc_ncomp(this) result(n)
        class(disc_family_t), intent(in) :: this   !! the family
        n = 6
    end function disc_ncomp

    !> Plate frames and neutral offsets from the neutral configuration.
    pure subroutine disc_neutral(this, kin)
        class(disc_family_t), intent(inout) :: this   !! the family; out: disc references set
        type(kinematics_t), intent(in) :: kin         !! kinematics of the neutral configuration
        integer :: e
        do e = 1, size(this%items)
            call disc_set_reference(this%items(e), kin)
        end do
    end subroutine disc_neutral

    !> The pre-strain: every disc's references (plate frames, neutral offset)
    !! measured in the displaced neutral configuration of kin, so that the
    !! discs are unstrained there and strained in the true neutral.
    pure subroutine disc_prestrain(this, kin, dx)
        class(disc_family_t), intent(inout) :: this   !! the family; out: disc references at kin
        type(kinematics_t), intent(in) :: kin         !! kinematics of the displaced neutral
        real(wp), intent(in) :: dx(:)                 !! the displacement [m, rad] (kin holds it)
        call this%set_neutral(kin)
    end subroutine disc_prestrain

    !> Loads of every disc; outputs their resultants.
    pure subroutine disc_loads(this, t, kin, x, xd, loads, out, work, energy)
        class(disc_family_t), intent(in) :: this      !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at (x, xd)
        real(wp), intent(in) :: x(:)                  !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)                 !! their rates [m/s, rad/s]
        type(body_loads_t), intent(inout) :: loads    !! loads, the discs' added
        real(wp), intent(inout) :: out(:, :)          !! (6, nd) resultants
        type(family_work_t), intent(inout) :: work    !! scratch (line geometry)
        type(family_energy_t), intent(inout) :: energy !! energy stored, power dissipated and absorbed, the family's added
        real(wp) :: u, pd
        integer :: e
        do e = 1, size(this%items)
            call apply_disc(this%items(e), kin, loads, out(:, e), u, pd)
            energy%u_elastic = energy%u_elastic + u
            energy%p_diss = energy%p_diss + pd
        end do
    end subroutine disc_loads

    !> K += B^T ds/dq B, C += B^T ds/dqd B of every disc (add_disc).
    pure subroutine disc_tangent(this, tree, kin, t, x, xd, kgen, cgen, tw)
        class(disc_family_t), intent(in) :: this      !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree
        type(kinematics_t), intent(in) :: kin         !! kinematics: joint columns filled
        real(wp), intent(in) :: t                     !! time [s]
        real(wp), intent(in) :: x(:)                  !! active coordinates
        real(wp), intent(in) :: xd(:)                 !! their rates
        real(wp), intent(inout) :: kgen(:, :)         !! generalized stiffness, the discs' added
        real(wp), intent(inout) :: cgen(:, :)         !! generalized damping, the discs' added
        type(tangent_work_t), intent(inout) :: tw     !! scratch sized for the coordinates
        integer :: e
        do e = 1, size(this%items)
            call add_disc(this%items(e), tree, kin, kgen, cgen, tw%cols, tw%sgn, tw%bd)
        end do
    end subroutine disc_tangent

    !> A disc: qd = B xdot with column B_i = +-G sj_i, G mapping a motion
    !! vector (w; v) to (L^T (v + w x (P_u - origin)); J^-1 L^T w) (P_u the
    !! upper plate centre where the loads act; + for the upper body's
    !! coordinates, - for the lower's); ds/dq and ds/dqd by central
    !! differences of disc_resultants.
    pure subroutine add_disc(d, tree, kin, kgen, cgen, cols, sgn, b)
        type(disc_t), intent(in) :: d
        type(body_tree_t), intent(in) :: tree
        type(kinematics_t), intent(in) :: kin
        real(wp), intent(inout) :: kgen(:, :), cgen(:, :)
        integer, intent(out) :: cols(:), sgn(:)   ! scratch, at least n long
        real(wp), intent(out) :: b(:, :)           ! scratch, (6, n)
        integer :: ncol, i, m
        real(wp) :: q(6), qd(6), l(3, 3), pup(3), ks(6, 6), cs(6, 6), dq(6), step, jinv(3, 3), pr(3)
        real(wp) :: w(3), v(3)
        call disc_deformation(d, kin, q, qd, l, pup)
        do m = 1, 6
            dq = zero
            step = max(fd_rel*abs(q(m)), fd_abs_length)
            dq(m) = step
            ks(:, m) = (disc_resultants(d, q + dq, qd) - disc_resultants(d, q - dq, qd))/(2*step)
            step = max(fd_rel*abs(qd(m)), fd_abs_rate)
            dq(m) = step
            cs(:, m) = (disc_resultants(d, q, qd + dq) - disc_resultants(d, q, qd - dq))/(2*step)
        end do
        jinv = inv_left_jacobian(q(4:6))
        pr = pup - kin%origin
        call path_columns(tree, d%body_a, d%body_b, cols, sgn, ncol)
        do i = 1, ncol
            w = kin%sj(1:3, cols(i))
            v = kin%sj(4:6, cols(i)) + cross(w, pr)
            b(1:3, i) = sgn(i)*matmul(v, l)
            b(4:6, i) = sgn(i)*matmul(jinv, matmul(w, l))
        end do
        kgen(cols(1:ncol), cols(1:ncol)) = kgen(cols(1:ncol), cols(1:ncol)) + &
                                           matmul(transpose(b(:, 1:ncol)), matmul(ks, b(:, 1:ncol)))
        cgen(cols(1:ncol), cols(1:ncol)) = cgen(cols(1:ncol), cols(1:ncol)) + &
                                           matmul(transpose(b(:, 1:ncol)), matmul(cs, b(:, 1:ncol)))
    end subroutine add_disc

    !> Discs never switch.
    pure integer function disc_switch_count(this) result(n)
        class(disc_family_t), intent(in) :: this   !! the family
        n = 0
    end function disc_switch_count

    !> No switching functions.
    pure subroutine disc_switching(this, t, kin, x, sw)
        class(disc_family_t), intent(in) :: this      !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at x
        real(wp), intent(in) :: x(:)                  !! active coordinates
        real(wp), intent(out) :: sw(:)                !! (0) none
        sw = zero
    end subroutine disc_switching

    !> Channels: every disc's axial force, then every shear x, then every moment y.
    pure function disc_channels(this, tree) result(c)
        class(disc_family_t), intent(in) :: this      !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree (unused)
        type(family_channel_t), allocatable :: c(:)
        integer :: e
        c = item_channels([(this%items(e)%name, e=1, size(this%items))], ['P ', 'VX', 'MY'], ['N  ', 'N  ', 'N m'], &
                          [character(len=13) :: 'DISC AXIAL', 'DISC SHEAR X', 'DISC MOMENT Y'], [3, 1, 5])
    end function disc_channels

    !> /model/elements/discs: plate centres, plate frames, area and thickness.
    pure function disc_table(this) result(tab)
        class(disc_family_t), intent(in) :: this      !! the family
        type(element_table_t) :: tab
        integer :: e, n
        n = size(this%items)
        tab%group = 'discs'
        tab%description = 'disc: lower plate centre (a, on body a) and upper plate centre (b, on body b)'
        allocate (tab%name(n))
        tab%name = [character(len=12) :: (this%items(e)%name, e=1, n)]
        tab%body = reshape([(this%items(e)%body_a, this%items(e)%body_b, e=1, n)], [2, n])
        tab%point = reshape([(this%items(e)%pa, this%items(e)%pb, e=1, n)], [3, 2, n])
        allocate (tab%extra(3))
        tab%extra(1)%name = 'plate_frame'
        tab%extra(1)%units = '1'
        tab%extra(1)%description = 'plate frames (lower, upper) in their body frames: h5py [e, plate, j, i] is R_ij'
        tab%extra(1)%r = [(this%items(e)%ra, this%items(e)%rb, e=1, n)]
        tab%extra(1)%shape = [3, 3, 2, n]
        tab%extra(2)%name = 'area'
        tab%extra(2)%units = 'm^2'
        tab%extra(2)%r = [(this%items(e)%area, e=1, n)]
        tab%extra(2)%shape = [n]
        tab%extra(3)%name = 'thickness'
        tab%extra(3)%units = 'm'
        tab%extra(3)%r = [(this%items(e)%h, e=1, n)]
        tab%extra(3)%shape = [n]
    end function disc_table

    !> Plate centres far outside their bodies; axial and bending stiffness far from the reference model's.
    pure subroutine disc_plausibility(this, tree, warnings)
        class(disc_family_t), intent(in) :: this      !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, the discs' added
        integer :: e
        do e = 1, size(this%items)
            associate (d => this%items(e))
                call check_point(tree, d%body_a, d%pa, 'disc '//d%name, warnings)
                call check_point(tree, d%body_b, d%pb, 'disc '//d%name, warnings)
                call check_range('disc '//trim(d%name)//' axial stiffness d1 A/h', d%d1*d%area/d%h, &
                                 ref_disc_axial, 'N/m', warnings)
                call check_range('disc '//trim(d%name)//' bending stiffness d1 Iy/h', d%d1*d%iy/d%h, &
                                 ref_disc_bending, 'N m/rad', warnings)
            end associate
        end do
    end subroutine disc_plausibility

    !> E, VISCOUS, G, VAXIAL, VBEND, VROT (d2r: bending and torsion damping alone), ETENSION, BEND (the
    !! second moments Ix, Iy), BENDX (Ix: lateral bending about the plate's x axis), BENDY (Iy:
    !! flexion-extension), TORSION (J).
    pure subroutine disc_items(this, items)
        class(disc_family_t), intent(in) :: this      !! the family
        character(len=item_len), intent(out) :: items(max_family_items)   !! the properties
        items = [character(len=item_len) :: 'E', 'VISCOUS', 'G', 'VAXIAL', 'VBEND', 'VROT', 'ETENSION', 'BEND', &
                                             'BENDX', 'BENDY', 'TORSION', 'LENGTH']
    end subroutine disc_items

    !> Scale one property of every disc (d2b not given becomes d2 from here on, d2r not given d2b).
    pure subroutine disc_scale(this, item, factor)
        class(disc_family_t), intent(inout) :: this   !! the family
        character(len=*), intent(in) :: item          !! one of disc_items
        real(wp), intent(in) :: factor                !! the factor
        where (this%items%d2b < zero) this%items%d2b = this%items%d2
        where (this%items%d2r < zero) this%items%d2r = this%items%d2b
        select case (item)
        case ('E'); this%items%d1 = factor*this%items%d1
        case ('VISCOUS')     ! every mode's damping
            this%items%d2 = factor*this%items%d2
            this%items%d2b = factor*this%items%d2b
            this%items%d2r = factor*this%items%d2r
        case ('VAXIAL'); this%items%d2 = factor*this%items%d2     ! axial damping (eq 1)
        case ('VBEND')       ! shear, bending, torsion damping
            this%items%d2b = factor*this%items%d2b
            this%items%d2r = factor*this%items%d2r
        case ('VROT'); this%items%d2r = factor*this%items%d2r     ! bending and torsion damping alone
        case ('G'); this%items%g = factor*this%items%g
        case ('ETENSION'); this%items%ft = factor*this%items%ft   ! axial stiffness in tension / d1's
        case ('BEND')        ! bending stiffness (and its damping) in both planes
            this%items%ix = factor*this%items%ix
            this%items%iy = factor*this%items%iy
        case ('BENDX'); this%items%ix = factor*this%items%ix      ! lateral bending (about plate x) alone
        case ('BENDY'); this%items%iy = factor*this%items%iy      ! flexion-extension (about plate y) alone
        case ('TORSION'); this%items%j = factor*this%items%j       ! torsion stiffness (and its damping)
        case ('LENGTH')      ! the geometry: A x factor^2, h x factor, Ix, Iy, J x factor^4
            this%items%area = factor**2*this%items%area
            this%items%h = factor*this%items%h
            this%items%ix = factor**4*this%items%ix
            this%items%iy = factor**4*this%items%iy
            this%items%j = factor**4*this%items%j
        end select
    end subroutine disc_scale

    !> STIFFEN: d1, d2, d2b, d2r and G (damping-to-stiffness ratios kept).
    pure subroutine disc_stiffen(this, factor)
        class(disc_family_t), intent(inout) :: this   !! the family
        real(wp), intent(in) :: factor                !! the factor
        this%items%d1 = factor*this%items%d1
        this%items%d2 = factor*this%items%d2
        this%items%d2b = factor*this%items%d2b
        this%items%d2r = factor*this%items%d2r
        this%items%g = factor*this%items%g
    end subroutine disc_stiffen

    !> The discs of a model's family slot (a copy; none when the slot holds another family).
    pure function discs_of(fam) result(items)
        class(element_family_t), intent(in) :: fam   !! the slot's family
        type(disc_t), allocatable :: items(:)
        select type (fam)
        type is (disc_family_t)
            items = fam%items
        class default
            allocate (items(0))
        end select
    end function discs_of

    !> A DISC card: the disc, kept unless both its plates are on one merged body.
    subroutine disc_read_card(this, rd, ctx, i, key)
        class(disc_family_t), intent(inout) :: this   !! the family; out: the disc added
        type(deck_reader_t), intent(inout) :: rd      !! the deck: card images, located field access, the first error
        type(card_context_t), intent(inout) :: ctx    !! the deck's bodies; out: ninternal counted
        integer, intent(in) :: i                      !! the card's first deck line
        character(len=*), intent(in) :: key           !! the card name (DISC)
        type(disc_t) :: d
        logical :: keep
        ! room for every DISC card, trimmed by end_cards (appending one by one is quadratic)
        if (ctx%needs_room(key, this%nread, size(this%items))) then
            deallocate (this%items)
            allocate (this%items(ctx%ncards(key)))
        end if
        call disc_card(rd, i, ctx%bnames, ctx%bmap, ctx%ninternal, d, keep)
        if (rd%failed()) return
        if (.not. keep) return
        this%nread = this%nread + 1
        this%items(this%nread) = d
    end subroutine disc_read_card

    !> The discs read: no room left over.
    subroutine disc_end_cards(this, rd, ctx)
        class(disc_family_t), intent(inout) :: this   !! the family; out: items trimmed to the discs read
        type(deck_reader_t), intent(inout) :: rd      !! the deck (unused)
        type(card_context_t), intent(inout) :: ctx    !! the deck's cards (unused)
        this%items = this%items(1:this%nread)
    end subroutine disc_end_cards

    !> A DISC card and its two continuation cards; keep is false for a disc
    !! inside one merged body.
    subroutine disc_card(rd, i, bnames, bmap, ninternal, d, keep)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        character(len=10), intent(in) :: bnames(:)  !! the names of the deck's bodies, in deck order
        type(body_map_t), intent(in) :: bmap  !! where each deck body went (MERGE), what locked its coordinates
        integer, intent(inout) :: ninternal  !! elements so far with both ends on one merged body
        type(disc_t), intent(out) :: d  !! the disc
        logical, intent(out) :: keep  !! false for a disc inside one merged body
        integer :: f
        real(wp) :: v
        d = disc_t()
        call rd%name(i, 1, 'disc name', d%name)
        d%body_a = body_ref(rd, i, 2, 'lower body', bnames, .false.)
        d%body_b = body_ref(rd, i, 3, 'upper body', bnames, .false.)
        call distinct_bodies(rd, i, d%body_a, d%body_b)
        call rd%real(i, 4, 'area A', 'm^2', d%area, 1.0e-8_wp, 1.0_wp)
        call rd%real(i, 5, 'thickness h', 'm', d%h, 1.0e-5_wp, 1.0_wp)
        call rd%real(i, 6, 'modulus d1', 'Pa', d%d1, 1.0e-3_wp, big_modulus)
        call rd%real(i, 7, 'viscous modulus d2', 'Pa s', d%d2, zero, big_modulus)
        do f = 1, 3
            call rd%real(i + 1, f, 'lower plate centre', 'm', d%pa(f), -big_length, big_length)
            call rd%real(i + 1, 3 + f, 'upper plate centre', 'm', d%pb(f), -big_length, big_length)
        end do
        call rd%real(i + 1, 7, 'plate tilt', 'deg', v, -90.0_wp, 90.0_wp, default=zero)
        d%tilt = v*deg
        call rd%real(i + 2, 1, 'shear modulus G', 'Pa', d%g, 1.0e-3_wp, big_modulus)
        call rd%real(i + 2, 2, 'second moment Ix', 'm^4', d%ix, 1.0e-20_wp, one)
        call rd%real(i + 2, 3, 'second moment Iy', 'm^4', d%iy, 1.0e-20_wp, one)
        call rd%real(i + 2, 4, 'torsion constant J', 'm^4', d%j, 1.0e-20_wp, one)
        call rd%real(i + 2, 5, 'shear factor k', '-', d%kshear, 0.1_wp, 10.0_wp, default=1.2_wp)
        call rd%real(i + 2, 6, 'viscous modulus d2b of shear, bending and torsion', 'Pa s', d%d2b, zero, &
                     big_modulus, default=d%d2)
        call rd%real(i + 2, 7, 'axial stiffness in tension as a fraction of d1''s', '-', d%ft, 1.0e-3_wp, one, &
                     default=one)
        if (rd%failed()) return
        call map_ends(bmap, d%body_a, d%pa, d%body_b, d%pb, ninternal)
        keep = d%body_a /= d%body_b
    end subroutine disc_card

    !> The registry's entry of the discs: name DISCS, its card DISC (two continuation
    !! cards), and the family with no elements.
    pure function disc_registration() result(r)
        type(family_registration_t) :: r
        r = family_registration_t('DISCS', [family_card_t('DISC', 0, 2, unique=unique_element)], disc_empty)
    end function disc_registration

    !> A family of discs with no elements (its arrays allocated with size 0, not
    !! taken from a zero-size array constructor, which gfortran copies into
    !! an unallocated component when the model is copied).
    pure subroutine disc_empty(slot)
        type(family_slot_t), intent(out) :: slot   !! the slot, holding the empty family
        type(disc_t), allocatable :: d(:)
        allocate (d(0)); allocate (slot%f, source=disc_family_t(items=d))
    end subroutine disc_empty

end module hn_disc_family
