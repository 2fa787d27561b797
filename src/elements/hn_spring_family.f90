!> The SPRINGS family: linear spring-dampers between two points
!! (hn_line_elements) behind the element-family interface. Output per
!! spring: its tension [N]. The family reads its SPRING cards.
module hn_spring_family
    use hn_kinds, only: wp, zero
    use hn_deck_reader, only: deck_reader_t
    use hn_element_cards, only: card_context_t, line_card, big_modulus
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t
    use hn_tree, only: body_tree_t
    use hn_line_elements, only: spring_t, line_geometry_t, line_geometries, spring_tension, spring_energy, &
                                apply_line_tensions, set_neutral_lengths, path_points, max_via
    use hn_element_family, only: element_family_t, family_work_t, family_channel_t, element_table_t, max_family_items, item_len
    use hn_line_family, only: line_family_t, line_table
    use hn_family_registration, only: family_registration_t
    use hn_element_cards, only: family_card_t, unique_element
    use hn_element_family, only: family_slot_t
    use hn_element_family, only: family_energy_t
    implicit none
    private

    public :: spring_family_t, springs_of
    public :: spring_registration

    !> The springs of a model.
    type, extends(line_family_t) :: spring_family_t
        type(spring_t), allocatable :: items(:)
        integer :: nread = 0   !! springs read from the deck so far (items holds room for every card until end_cards)
    contains
        procedure :: read_card => spring_read_card
        procedure :: end_cards => spring_end_cards
        procedure :: count => spring_count
        procedure :: ncomp => spring_ncomp
        procedure :: set_neutral => spring_neutral
        procedure :: add_loads => spring_loads
        procedure :: switch_count => spring_switch_count
        procedure :: switching => spring_switching
        procedure :: channels => spring_channels
        procedure :: result_table => spring_table
        procedure :: path => spring_path
        procedure :: line_tension => spring_line_tension
        procedure :: line_kind => spring_kind
        procedure :: scale_items => spring_items
        procedure :: scale => spring_scale
        procedure :: stiffen => spring_stiffen
    end type spring_family_t

contains

    !> Number of springs.
    pure integer function spring_count(this) result(n)
        class(spring_family_t), intent(in) :: this   !! the family
        n = 0
        if (allocated(this%items)) n = size(this%items)
    end function spring_count

    !> Output rows per spring: its tension.
    pure integer function spring_ncomp(this) result(n)
        class(spring_family_t), intent(in) :: this   !! the family
        n = 1
    end function spring_ncomp

    !> Free lengths not given: the neutral lengths.
    pure subroutine spring_neutral(this, kin)
        class(spring_family_t), intent(inout) :: this   !! the family; out: free lengths set
        type(kinematics_t), intent(in) :: kin           !! kinematics of the neutral configuration
        call set_neutral_lengths(kin, this%items)
    end subroutine spring_neutral

    !> Tensions of every spring applied to its bodies; stored energy, dissipated power.
    pure subroutine spring_loads(this, t, kin, x, xd, loads, out, work, energy)
        class(spring_family_t), intent(in) :: this    !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at (x, xd)
        real(wp), intent(in) :: x(:)                  !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)                 !! their rates [m/s, rad/s]
        type(body_loads_t), intent(inout) :: loads    !! loads, the springs' added
        real(wp), intent(inout) :: out(:, :)          !! (1, ns) tension [N]
        type(family_work_t), intent(inout) :: work    !! scratch (line geometry)
        type(family_energy_t), intent(inout) :: energy !! energy stored, power dissipated and absorbed, the family's added
        associate (gs => work%g)
            call line_geometries(kin, this%items, gs)
            out(1, :) = spring_tension(this%items, gs%length, gs%rate)
            call apply_line_tensions(loads, kin, this%items, gs, out(1, :))
            energy%u_elastic = energy%u_elastic + sum(spring_energy(this%items, gs%length))
            energy%p_diss = energy%p_diss + sum(this%items%damping*gs%rate**2)
        end associate
    end subroutine spring_loads

    !> Springs never switch.
    pure integer function spring_switch_count(this) result(n)
        class(spring_family_t), intent(in) :: this   !! the family
        n = 0
    end function spring_switch_count

    !> No switching functions.
    pure subroutine spring_switching(this, t, kin, x, sw)
        class(spring_family_t), intent(in) :: this    !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at x (unused)
        real(wp), intent(in) :: x(:)                  !! active coordinates (unused)
        real(wp), intent(out) :: sw(:)                !! (0) none
        sw = zero
    end subroutine spring_switching

    !> No channels (springs are fixtures of test models and scenes, not listed).
    pure function spring_channels(this, tree) result(c)
        class(spring_family_t), intent(in) :: this    !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree (unused)
        type(family_channel_t), allocatable :: c(:)
        allocate (c(0))
    end function spring_channels

    !> /model/elements/springs; springs have no name in the deck: SPRING1, SPRING2, ...
    pure function spring_table(this) result(tab)
        class(spring_family_t), intent(in) :: this    !! the family
        type(element_table_t) :: tab
        integer :: e
        tab = line_table(this, 'springs', 'linear spring-damper from point a to b')
        do e = 1, size(this%items)
            write (tab%name(e), '(a, i0)') 'SPRING', e
        end do
    end function spring_table

    !> Spring e's name and its two ends.
    pure subroutine spring_path(this, e, name, bodies, points, npt)
        class(spring_family_t), intent(in) :: this        !! the family
        integer, intent(in) :: e                          !! spring number
        character(len=12), intent(out) :: name            !! its name
        integer, intent(out) :: bodies(max_via + 2)       !! the ends' bodies
        real(wp), intent(out) :: points(3, max_via + 2)   !! their body-frame positions [m]
        integer, intent(out) :: npt                       !! 2
        name = this%items(e)%name
        call path_points(this%items(e), bodies, points, npt)
    end subroutine spring_path

    !> Spring e's tension k (L - L0) + c L'.
    pure real(wp) function spring_line_tension(this, e, t, length, rate) result(tension)
        class(spring_family_t), intent(in) :: this   !! the family
        integer, intent(in) :: e                     !! spring number
        real(wp), intent(in) :: t                    !! time [s] (unused)
        real(wp), intent(in) :: length               !! length [m]
        real(wp), intent(in) :: rate                 !! its rate [m/s]
        tension = spring_tension(this%items(e), length, rate)
    end function spring_line_tension

    !> 'spring'.
    pure function spring_kind(this) result(word)
        class(spring_family_t), intent(in) :: this   !! the family
        character(len=:), allocatable :: word
        word = 'spring'
    end function spring_kind

    !> K, C.
    pure subroutine spring_items(this, items)
        class(spring_family_t), intent(in) :: this    !! the family
        character(len=item_len), intent(out) :: items(max_family_items)   !! the properties
        items = ''
        items(1:2) = [character(len=item_len) :: 'K', 'C']
    end subroutine spring_items

    !> Scale the stiffness or damping of every spring.
    pure subroutine spring_scale(this, item, factor)
        class(spring_family_t), intent(inout) :: this   !! the family
        character(len=*), intent(in) :: item            !! K or C
        real(wp), intent(in) :: factor                  !! the factor
        select case (item)
        case ('K'); this%items%stiffness = factor*this%items%stiffness
        case ('C'); this%items%damping = factor*this%items%damping
        end select
    end subroutine spring_scale

    !> STIFFEN: the stiffness.
    pure subroutine spring_stiffen(this, factor)
        class(spring_family_t), intent(inout) :: this   !! the family
        real(wp), intent(in) :: factor                  !! the factor
        this%items%stiffness = factor*this%items%stiffness
    end subroutine spring_stiffen

    !> The springs of a model's family slot (a copy; none when the slot holds another family).
    pure function springs_of(fam) result(items)
        class(element_family_t), intent(in) :: fam   !! the slot's family
        type(spring_t), allocatable :: items(:)
        select type (fam)
        type is (spring_family_t)
            items = fam%items
        class default
            allocate (items(0))
        end select
    end function springs_of

    !> A SPRING card: name, bodies, stiffness, damping; the attachment
    !! points and free length on its continuation card. Kept unless both
    !! ends are on one merged body.
    subroutine spring_read_card(this, rd, ctx, i, key)
        class(spring_family_t), intent(inout) :: this   !! the family; out: the spring added
        type(deck_reader_t), intent(inout) :: rd        !! the deck: card images, located field access, the first error
        type(card_context_t), intent(inout) :: ctx      !! the deck's bodies; out: ninternal counted
        integer, intent(in) :: i                        !! the card's first deck line
        character(len=*), intent(in) :: key             !! the card name (SPRING)
        type(spring_t) :: sp
        logical :: keep
        ! room for every SPRING card, trimmed by end_cards (appending one by one is quadratic)
        if (ctx%needs_room(key, this%nread, size(this%items))) then
            deallocate (this%items)
            allocate (this%items(ctx%ncards(key)))
        end if
        sp = spring_t()
        call line_card(rd, ctx, i, 'spring', sp%line_attach_t, i, 6, keep)
        call rd%real(i, 4, 'stiffness', 'N/m', sp%stiffness, zero, big_modulus)
        call rd%real(i, 5, 'damping', 'N s/m', sp%damping, zero, big_modulus, default=zero)
        if (.not. keep .or. rd%failed()) return
        this%nread = this%nread + 1
        this%items(this%nread) = sp
    end subroutine spring_read_card

    !> The springs read: no room left over.
    subroutine spring_end_cards(this, rd, ctx)
        class(spring_family_t), intent(inout) :: this   !! the family; out: items trimmed to the springs read
        type(deck_reader_t), intent(inout) :: rd        !! the deck (unused)
        type(card_context_t), intent(inout) :: ctx      !! the deck's cards (unused)
        this%items = this%items(1:this%nread)
    end subroutine spring_end_cards

    !> The registry's entry of the springs: name SPRINGS, its card SPRING, and the
    !! family with no elements.
    pure function spring_registration() result(r)
        type(family_registration_t) :: r
        r = family_registration_t('SPRINGS', [family_card_t('SPRING', 0, 1, unique=unique_element)], spring_empty)
    end function spring_registration

    !> A family of springs with no elements (its arrays allocated with size 0, not
    !! taken from a zero-size array constructor, which gfortran copies into
    !! an unallocated component when the model is copied).
    pure subroutine spring_empty(slot)
        type(family_slot_t), intent(out) :: slot   !! the slot, holding the empty family
        type(spring_t), allocatable :: sp(:)
        allocate (sp(0)); allocate (slot%f, source=spring_family_t(items=sp))
    end subroutine spring_empty

end module hn_spring_family
