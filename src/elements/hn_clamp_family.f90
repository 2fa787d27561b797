!> The CLAMPS family: a body held to a rig by a stiff six-axis joint, the
!! support of a test fixture (a head clamped to a twist rig, a vertebra in
!! a pot). Between a point of the body and the rig's point that coincided
!! with it in the neutral configuration act a translational spring-damper
!! (kt, ct) on their separation and a rotational one (kr, cr) on the body's
!! rotation from its neutral orientation relative to the rig (the rotation
!! vector of the difference) and on their relative angular velocity. The
!! rig is R (the lab) or a body of the tree (it then moves as that body
!! does, prescribed or not), and it may turn about an axis through the
!! clamp's point by an angular-velocity table, integrated exactly to the
!! rig's angle (hn_motion's rate table). The load on the body and its
!! reaction on the rig body are the clamp's own channels (NAME_FX ...
!! NAME_MZ on the body in R, the deflection NAME_D [mm], the rotation
!! NAME_R [deg] and the rig's angle NAME_A [deg]); the load cells and
!! sections leave it out (hn_sections: a support of the fixture, not a load
!! through the specimen).
module hn_clamp_family
    use hn_kinds, only: wp, zero, one, half
    use hn_deck_reader, only: deck_reader_t
    use hn_element_cards, only: card_context_t, body_ref, table_ref, map_ends, big_length, big_modulus
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t, add_force_pair
    use hn_tree, only: body_tree_t
    use hn_tables, only: table_t
    use hn_family_registration, only: family_registration_t
    use hn_element_cards, only: family_card_t, unique_element
    use hn_element_family, only: family_slot_t, item_channels
    use hn_motion, only: motion_t, motion_rate_table, motion_constant, motion_eval
    use hn_rotation, only: cross, rotation_vector, axis_angle_matrix, unit_matrix
    use hn_element_family, only: element_family_t, family_work_t, family_channel_t, element_table_t, table_data_t, &
                                 max_family_items, item_len, warning_len, check_point, add_line_tangent, spatial_row
    use hn_element_family, only: family_energy_t, tangent_work_t
    implicit none
    private

    public :: clamp_family_t, clamp_t, clamp_load
    public :: clamp_registration

    integer, parameter :: ncomp_clamp = 9   !! output rows: force (3), moment (3), deflection, rotation, rig angle

    !> One clamp: the body held, the rig, the joint's stiffness and damping,
    !! the clamp's point and the references of the neutral configuration.
    type :: clamp_t
        character(len=10) :: name = ''
        integer :: body = 0                     !! the body held
        integer :: rig = 0                      !! the rig's body (0 = R)
        real(wp) :: kt = zero, ct = zero        !! translational stiffness [N/m] and damping [N s/m]
        real(wp) :: kr = zero, cr = zero        !! rotational stiffness [N m/rad] and damping [N m s/rad]
        real(wp) :: point(3) = zero             !! the clamp's point in the body's frame from its mass centre [m]
        real(wp) :: rig_point(3) = zero         !! the same point in the rig's frame at neutral [m]
        real(wp) :: a0(3, 3) = reshape([one, zero, zero, zero, one, zero, zero, zero, one], [3, 3])
                                                !! the body's orientation in the rig's frame at neutral
        real(wp) :: axis(3) = [zero, zero, one] !! the rig's turning axis in the rig body's frame (unit)
        logical :: turns = .false.              !! the rig turns by an angular-velocity table
        type(motion_t) :: turn                  !! the rig's angle about axis [rad]
    end type clamp_t

    !> The clamps of a model and the rigs' angular-velocity tables.
    type, extends(element_family_t) :: clamp_family_t
        type(clamp_t), allocatable :: items(:)
        type(table_t), allocatable :: tables(:)   !! the rigs' angular-velocity tables [rad/s]
        integer :: nread = 0   !! clamps read from the deck so far (items holds room for every card until end_cards)
    contains
        procedure :: read_card => clamp_read_card
        procedure :: end_cards => clamp_end_cards
        procedure :: count => clamp_count
        procedure :: ncomp => clamp_ncomp
        procedure :: set_neutral => clamp_neutral
        procedure :: add_loads => clamp_loads
        procedure :: add_tangent => clamp_tangent
        procedure :: switch_count => clamp_switch_count
        procedure :: switching => clamp_switching
        procedure :: channels => clamp_channels
        procedure :: result_table => clamp_table
        procedure :: plausibility => clamp_plausibility
        procedure :: scale_items => clamp_items
        procedure :: scale => clamp_scale
        procedure :: stiffen => clamp_stiffen
        procedure :: input_tables => clamp_input_tables
    end type clamp_family_t

contains

    !> Number of clamps.
    pure integer function clamp_count(this) result(n)
        class(clamp_family_t), intent(in) :: this   !! the family
        n = 0
        if (allocated(this%items)) n = size(this%items)
    end function clamp_count

    !> Output rows per clamp: force (3), moment (3), deflection, rotation, rig angle.
    pure integer function clamp_ncomp(this) result(n)
        class(clamp_family_t), intent(in) :: this   !! the family
        n = ncomp_clamp
    end function clamp_ncomp

    !> No switching functions: a clamp's law is smooth.
    pure integer function clamp_switch_count(this) result(n)
        class(clamp_family_t), intent(in) :: this   !! the family (unused)
        n = 0
    end function clamp_switch_count

    !> Nothing switches.
    pure subroutine clamp_switching(this, t, kin, x, sw)
        class(clamp_family_t), intent(in) :: this   !! the family (unused)
        real(wp), intent(in) :: t                   !! time [s] (unused)
        type(kinematics_t), intent(in) :: kin       !! kinematics (unused)
        real(wp), intent(in) :: x(:)                !! active coordinates (unused)
        real(wp), intent(out) :: sw(:)              !! (0) none
        sw = zero
    end subroutine clamp_switching

    !> The references of the neutral configuration: the clamp's point in
    !! the rig's frame and the body's orientation relative to the rig.
    pure subroutine clamp_neutral(this, kin)
        class(clamp_family_t), intent(inout) :: this   !! the family; out: references set
        type(kinematics_t), intent(in) :: kin          !! kinematics of the neutral configuration
        real(wp) :: p(3), sa(3, 3), ra(3)
        integer :: e
        do e = 1, size(this%items)
            associate (c => this%items(e))
                p = kin%r(:, c%body) + matmul(kin%s(:, :, c%body), c%point)
                call rig_frame(kin, c%rig, sa, ra)
                c%rig_point = matmul(transpose(sa), p - ra)
                c%a0 = matmul(transpose(sa), kin%s(:, :, c%body))
            end associate
        end do
    end subroutine clamp_neutral

    !> The rig body's rotation matrix and mass centre (R: unit, origin).
    pure subroutine rig_frame(kin, rig, sa, ra)
        type(kinematics_t), intent(in) :: kin   !! kinematics
        integer, intent(in) :: rig              !! the rig's body (0 = R)
        real(wp), intent(out) :: sa(3, 3)       !! its body-to-R matrix
        real(wp), intent(out) :: ra(3)          !! its mass centre in R [m]
        if (rig > 0) then
            sa = kin%s(:, :, rig); ra = kin%r(:, rig)
        else
            sa = unit_matrix(); ra = zero
        end if
    end subroutine rig_frame

    !> The load of clamp c at time t: the force f and couple m on the held
    !! body in R, applied at the point p in R (the rig takes -f, -m there),
    !! the separation d [m] and rotation phi [rad] (in R) and the rig's angle
    !! [rad], the relative velocity and angular velocity, and the power the
    !! rig's own turning puts in (the clamp's load on the system less what
    !! its springs store and its dampers dissipate). Also what hn_sections
    !! subtracts from a section's load.
    pure subroutine clamp_load(kin, c, t, p, f, m, d, phi, angle, rel, p_rig)
        type(kinematics_t), intent(in) :: kin   !! kinematics
        type(clamp_t), intent(in) :: c          !! the clamp
        real(wp), intent(in) :: t               !! time [s]
        real(wp), intent(out) :: p(3)           !! the body's clamp point in R [m]
        real(wp), intent(out) :: f(3)           !! force on the body in R [N]
        real(wp), intent(out) :: m(3)           !! couple on the body in R [N m]
        real(wp), intent(out) :: d(3)           !! the point's separation from the rig's [m]
        real(wp), intent(out) :: phi(3)         !! the body's rotation from its clamped orientation in R [rad]
        real(wp), intent(out) :: angle          !! the rig's angle about its axis [rad]
        real(wp), intent(out) :: rel(6)         !! the point's velocity relative to the rig's [m/s], then the
                                                !! body's angular velocity relative to the rig's [rad/s], in R
        real(wp), intent(out) :: p_rig          !! power the turning rig puts in [W]
        real(wp) :: sa(3, 3), ra(3), srig(3, 3), pa(3), va(3), wa(3), vb(3), rate, acc, u(3)
        call rig_frame(kin, c%rig, sa, ra)
        angle = zero; rate = zero
        if (c%turns) call motion_eval(c%turn, t, angle, rate, acc)
        u = matmul(sa, c%axis)
        srig = matmul(axis_angle_matrix(angle*u), sa)
        pa = ra + matmul(sa, c%rig_point)
        va = zero; wa = zero
        if (c%rig > 0) then
            wa = kin%omega(:, c%rig)
            va = kin%v(:, c%rig) + cross(wa, pa - ra)
        end if
        wa = wa + rate*u
        p = kin%r(:, c%body) + matmul(kin%s(:, :, c%body), c%point)
        vb = kin%v(:, c%body) + cross(kin%omega(:, c%body), p - kin%r(:, c%body))
        d = p - pa
        phi = rotation_vector(matmul(kin%s(:, :, c%body), transpose(matmul(srig, c%a0))))
        rel = [vb - va, kin%omega(:, c%body) - wa]
        f = -c%kt*d - c%ct*rel(1:3)
        m = -c%kr*phi - c%cr*rel(4:6)
        ! the pair's power on the tree, f.(v_b(p) - v_a(p)) + m.(w_b - w_a), is
        ! -(stored + dissipated) + m.(rate u) + f.(w_a x (pa - p))
        p_rig = dot_product(m, rate*u) + dot_product(f, cross(wa - rate*u, pa - p))
    end subroutine clamp_load

    !> The load of every clamp on its body and the reaction on its rig;
    !! stored energy (both springs) and dissipated power (both dampers, less
    !! the power a turning rig puts in: the energy balance's external work).
    pure subroutine clamp_loads(this, t, kin, x, xd, loads, out, work, energy)
        class(clamp_family_t), intent(in) :: this     !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at (x, xd)
        real(wp), intent(in) :: x(:)                  !! active coordinates [m, rad] (unused)
        real(wp), intent(in) :: xd(:)                 !! their rates [m/s, rad/s] (unused)
        type(body_loads_t), intent(inout) :: loads    !! loads, the clamps' added
        real(wp), intent(inout) :: out(:, :)          !! (9, n) force [N], moment [N m], deflection [mm],
                                                      !! rotation [deg], rig angle [deg]
        type(family_work_t), intent(inout) :: work    !! scratch (unused)
        type(family_energy_t), intent(inout) :: energy !! energy stored, power dissipated and absorbed, the family's added
        real(wp), parameter :: deg = 180.0_wp/acos(-one)
        real(wp) :: p(3), f(3), m(3), d(3), phi(3), angle, rel(6), ra(3), sa(3, 3), p_rig
        integer :: e
        do e = 1, size(this%items)
            associate (c => this%items(e))
                call clamp_load(kin, c, t, p, f, m, d, phi, angle, rel, p_rig)
                out(:, e) = [f, m, 1000*norm2(d), deg*norm2(phi), deg*angle]
                call rig_frame(kin, c%rig, sa, ra)
                call add_force_pair(loads, c%rig, ra, c%body, kin%r(:, c%body), p, f, m)
                energy%u_elastic = energy%u_elastic + half*(c%kt*dot_product(d, d) + c%kr*dot_product(phi, phi))
                energy%p_diss = energy%p_diss + c%ct*dot_product(rel(1:3), rel(1:3)) + c%cr*dot_product(rel(4:6), rel(4:6)) - p_rig
            end associate
        end do
    end subroutine clamp_loads

    !> The row b_j of the relative rate of body kb to the rig ka along u:
    !! translational (the velocity of the material point p, spatial force
    !! ((p - origin) x u; u)) or rotational (the angular velocity, (u; 0)).
    pure subroutine clamp_row(tree, kin, ka, kb, p, u, rotational, cols, sgn, b)
        type(body_tree_t), intent(in) :: tree        !! the body tree
        type(kinematics_t), intent(in) :: kin        !! kinematics: joint columns filled
        integer, intent(in) :: ka                    !! the rig's body (0 = R)
        integer, intent(in) :: kb                    !! the body held
        real(wp), intent(in) :: p(3)                 !! the clamp's point in R [m]
        real(wp), intent(in) :: u(3)                 !! the direction in R
        logical, intent(in) :: rotational            !! the angular velocity's row (else the point's velocity)
        integer, intent(out) :: cols(:)              !! scratch
        integer, intent(out) :: sgn(:)               !! scratch
        real(wp), intent(out) :: b(:)                !! (n) the row
        if (rotational) then
            call spatial_row(tree, kin, ka, kb, [u, zero, zero, zero], cols, sgn, b)
        else
            call spatial_row(tree, kin, ka, kb, [cross(p - kin%origin, u), u], cols, sgn, b)
        end if
    end subroutine clamp_row

    !> K += kt b b^T, C += ct b b^T along R's three axes for the point's
    !! separation, and kr, cr for the relative rotation (the joint's small-
    !! deflection tangent: a stiff clamp is held near its reference).
    pure subroutine clamp_tangent(this, tree, kin, t, x, xd, kgen, cgen, tw)
        class(clamp_family_t), intent(in) :: this     !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree
        type(kinematics_t), intent(in) :: kin         !! kinematics: joint columns filled
        real(wp), intent(in) :: t                     !! time [s] (unused)
        real(wp), intent(in) :: x(:)                  !! active coordinates (unused)
        real(wp), intent(in) :: xd(:)                 !! their rates (unused)
        real(wp), intent(inout) :: kgen(:, :)         !! generalized stiffness, the clamps' added
        real(wp), intent(inout) :: cgen(:, :)         !! generalized damping, the clamps' added
        type(tangent_work_t), intent(inout) :: tw     !! scratch sized for the coordinates
        real(wp) :: p(3), ax(3)
        integer :: e, i
        do e = 1, size(this%items)
            associate (c => this%items(e))
                p = kin%r(:, c%body) + matmul(kin%s(:, :, c%body), c%point)
                do i = 1, 3
                    ax = zero; ax(i) = one
                    call clamp_row(tree, kin, c%rig, c%body, p, ax, .false., tw%cols, tw%sgn, tw%b)
                    call add_line_tangent(tw%b, c%kt, c%ct, kgen, cgen, tw%idx)
                    call clamp_row(tree, kin, c%rig, c%body, p, ax, .true., tw%cols, tw%sgn, tw%b)
                    call add_line_tangent(tw%b, c%kr, c%cr, kgen, cgen, tw%idx)
                end do
            end associate
        end do
    end subroutine clamp_tangent

    !> NAME_FX ... NAME_MZ the load on the body in R [N, N m], NAME_D the
    !! deflection [mm], NAME_R the rotation [deg], NAME_A the rig's angle [deg].
    pure function clamp_channels(this, tree) result(c)
        class(clamp_family_t), intent(in) :: this   !! the family
        type(body_tree_t), intent(in) :: tree       !! the body tree (unused)
        type(family_channel_t), allocatable :: c(:)
        character(len=2), parameter :: suffix(ncomp_clamp) = ['FX', 'FY', 'FZ', 'MX', 'MY', 'MZ', 'D ', 'R ', 'A ']
        character(len=3), parameter :: units(ncomp_clamp) = ['N  ', 'N  ', 'N  ', 'N m', 'N m', 'N m', 'mm ', &
                                                              'deg', 'deg']
        integer :: e
        c = item_channels([(this%items(e)%name, e=1, size(this%items))], suffix, units, &
                          [('CLAMP', e=1, ncomp_clamp)], [(e, e=1, ncomp_clamp)])
    end function clamp_channels

    !> /model/elements/clamps: body a the rig (0 = R), b the body held;
    !! points the clamp's point in each; the stiffnesses and dampings.
    pure function clamp_table(this) result(tab)
        class(clamp_family_t), intent(in) :: this   !! the family
        type(element_table_t) :: tab
        integer :: e, n
        n = size(this%items)
        tab%group = 'clamps'
        tab%description = 'body b held to the rig a by a six-axis spring-damper at its point'
        allocate (tab%name(n), tab%extra(1))
        tab%name = this%items%name
        tab%body = reshape([(this%items(e)%rig, this%items(e)%body, e=1, n)], [2, n])
        tab%point = reshape([(this%items(e)%rig_point, this%items(e)%point, e=1, n)], [3, 2, n])
        tab%extra(1) = table_data_t('law', 'SI', 'kt [N/m], ct [N s/m], kr [N m/rad], cr [N m s/rad]', &
                                    r=[(this%items(e)%kt, this%items(e)%ct, this%items(e)%kr, this%items(e)%cr, &
                                        e=1, n)], shape=[4, n])
    end function clamp_table

    !> Clamp points far outside their bodies.
    pure subroutine clamp_plausibility(this, tree, warnings)
        class(clamp_family_t), intent(in) :: this   !! the family
        type(body_tree_t), intent(in) :: tree       !! the body tree
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, the clamps' added
        integer :: e
        do e = 1, size(this%items)
            call check_point(tree, this%items(e)%body, this%items(e)%point, 'clamp '//this%items(e)%name, warnings)
        end do
    end subroutine clamp_plausibility

    !> K (both stiffnesses), C (both dampings).
    pure subroutine clamp_items(this, items)
        class(clamp_family_t), intent(in) :: this   !! the family
        character(len=item_len), intent(out) :: items(max_family_items)   !! the properties
        items = ''
        items(1:2) = [character(len=item_len) :: 'K', 'C']
    end subroutine clamp_items

    !> Scale the stiffnesses or the dampings of every clamp.
    pure subroutine clamp_scale(this, item, factor)
        class(clamp_family_t), intent(inout) :: this   !! the family
        character(len=*), intent(in) :: item           !! K or C
        real(wp), intent(in) :: factor                 !! the factor
        select case (item)
        case ('K'); call clamp_stiffen(this, factor)
        case ('C'); this%items%ct = factor*this%items%ct; this%items%cr = factor*this%items%cr
        end select
    end subroutine clamp_scale

    !> STIFFEN: both stiffnesses.
    pure subroutine clamp_stiffen(this, factor)
        class(clamp_family_t), intent(inout) :: this   !! the family
        real(wp), intent(in) :: factor                 !! the factor
        this%items%kt = factor*this%items%kt
        this%items%kr = factor*this%items%kr
    end subroutine clamp_stiffen

    !> The rigs' angular-velocity tables: the run's steps land on their corners.
    pure function clamp_input_tables(this) result(tabs)
        class(clamp_family_t), intent(in) :: this   !! the family
        type(table_t), allocatable :: tabs(:)
        tabs = this%tables
    end function clamp_input_tables

    !> A CLAMP card (docs/deck-format.md): name, the body held, the rig (R
    !! or a body), kt, ct, kr, cr; the clamp's point on the body (F1-F3),
    !! the rig's angular-velocity table (F4, blank: the rig does not turn)
    !! and its axis in the rig's frame (F5-F7, default z) on the
    !! continuation card.
    subroutine clamp_read_card(this, rd, ctx, i, key)
        class(clamp_family_t), intent(inout) :: this   !! the family; out: the clamp added
        type(deck_reader_t), intent(inout) :: rd       !! the deck: card images, located field access, the first error
        type(card_context_t), intent(inout) :: ctx     !! the deck's bodies and tables; out: ninternal counted
        integer, intent(in) :: i                       !! the card's first deck line
        character(len=*), intent(in) :: key            !! the card name (CLAMP)
        real(wp), parameter :: big_rot = 1.0e9_wp
        type(clamp_t) :: c
        character(len=10) :: nm
        real(wp) :: rig_point(3)
        integer :: f, it, stat
        if (ctx%needs_room(key, this%nread, size(this%items))) then
            deallocate (this%items)
            allocate (this%items(ctx%ncards(key)))
        end if
        call rd%name(i, 1, 'clamp name', nm)
        c%name = nm
        c%body = body_ref(rd, i, 2, 'body held', ctx%bnames, .false.)
        c%rig = body_ref(rd, i, 3, 'rig', ctx%bnames, .true.)
        if (.not. rd%failed() .and. c%body == c%rig) &
            call rd%fail(rd%context(i, 3, 'rig')//': found the body held again; expected another body or R')
        call rd%real(i, 4, 'translational stiffness', 'N/m', c%kt, zero, big_modulus)
        call rd%real(i, 5, 'translational damping', 'N s/m', c%ct, zero, big_modulus, default=zero)
        call rd%real(i, 6, 'rotational stiffness', 'N m/rad', c%kr, zero, big_rot)
        call rd%real(i, 7, 'rotational damping', 'N m s/rad', c%cr, zero, big_rot, default=zero)
        do f = 1, 3
            call rd%real(i + 1, f, 'clamp point', 'm', c%point(f), -big_length, big_length, default=zero)
        end do
        do f = 1, 3
            call rd%real(i + 1, 4 + f, 'rig axis', '-', c%axis(f), -big_modulus, big_modulus, &
                         default=merge(one, zero, f == 3))
        end do
        if (rd%failed()) return
        if (all(c%axis == zero)) then
            call rd%fail(rd%where(i + 1)//', columns 51-80 (CLAMP card continuation, fields F5-F7 ''rig axis''): '// &
                         'found a zero vector; expected the axis the rig turns about, in the rig''s frame')
            return
        end if
        c%axis = c%axis/norm2(c%axis)
        if (.not. rd%is_blank(i + 1, 4)) then
            it = table_ref(rd, i + 1, 4, ctx%tabs)
            if (rd%failed()) return
            call motion_rate_table(c%turn, ctx%tabs(it)%tab%t, ctx%tabs(it)%tab%y, zero, stat)
            c%turns = .true.
            this%tables = [this%tables, ctx%tabs(it)%tab]
        else
            c%turn = motion_constant(zero)
        end if
        rig_point = zero
        call map_ends(ctx%bmap, c%rig, rig_point, c%body, c%point, ctx%ninternal)
        if (c%body == c%rig) return     ! both on one merged body: dropped
        this%nread = this%nread + 1
        this%items(this%nread) = c
    end subroutine clamp_read_card

    !> The clamps read: no room left over.
    subroutine clamp_end_cards(this, rd, ctx)
        class(clamp_family_t), intent(inout) :: this   !! the family; out: items trimmed to the clamps read
        type(deck_reader_t), intent(inout) :: rd       !! the deck (unused)
        type(card_context_t), intent(inout) :: ctx     !! the deck's cards (unused)
        this%items = this%items(1:this%nread)
    end subroutine clamp_end_cards

    !> The registry's entry of the clamps: name CLAMPS, its card CLAMP (one
    !! continuation card), and the family with no elements.
    pure function clamp_registration() result(r)
        type(family_registration_t) :: r
        r = family_registration_t('CLAMPS', [family_card_t('CLAMP', 0, 1, unique=unique_element)], clamp_empty)
    end function clamp_registration

    !> A family of clamps with no elements (its arrays allocated with size 0, not
    !! taken from a zero-size array constructor, which gfortran copies into
    !! an unallocated component when the model is copied).
    pure subroutine clamp_empty(slot)
        type(family_slot_t), intent(out) :: slot   !! the slot, holding the empty family
        type(clamp_t), allocatable :: cl(:)
        type(table_t), allocatable :: tb(:)
        allocate (cl(0), tb(0)); allocate (slot%f, source=clamp_family_t(items=cl, tables=tb))
    end subroutine clamp_empty

end module hn_clamp_family
