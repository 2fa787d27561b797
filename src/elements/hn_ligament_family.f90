!> The LIGAMENTS family: tension-only bands (eq 10, hn_line_elements)
!! behind the element-family interface. Output per ligament: tension [N]
!! and length [m]. The family reads its LIGAMENT cards.
module hn_ligament_family
    use hn_kinds, only: wp, zero, one
    use hn_deck_reader, only: deck_reader_t
    use hn_element_cards, only: card_context_t, line_card, big_modulus
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t
    use hn_tree, only: body_tree_t
    use hn_line_elements, only: ligament_t, line_geometry_t, line_geometries, ligament_tension, ligament_energy, &
                                apply_line_tensions, set_neutral_lengths, path_points, max_via
    use hn_element_family, only: element_family_t, family_work_t, family_channel_t, element_table_t, max_family_items, item_len, &
                                 warning_len, check_range
    use hn_line_family, only: line_family_t, line_table
    use hn_family_registration, only: family_registration_t
    use hn_element_cards, only: family_card_t, unique_element
    use hn_element_family, only: family_slot_t
    use hn_element_family, only: family_energy_t
    implicit none
    private

    public :: ligament_family_t, ligaments_of
    public :: ligament_registration

    real(wp), parameter :: ref_ligament_2mm = 30.0_wp     !! N at 2 mm stretch (reference/parameters.md)

    !> The ligaments of a model.
    type, extends(line_family_t) :: ligament_family_t
        type(ligament_t), allocatable :: items(:)
        integer :: nread = 0   !! ligaments read from the deck so far (items holds room for every card until end_cards)
    contains
        procedure :: read_card => ligament_read_card
        procedure :: end_cards => ligament_end_cards
        procedure :: count => ligament_count
        procedure :: ncomp => ligament_ncomp
        procedure :: set_neutral => ligament_neutral
        procedure :: add_loads => ligament_loads
        procedure :: switch_count => ligament_switch_count
        procedure :: switching => ligament_switching
        procedure :: channels => ligament_channels
        procedure :: result_table => ligament_table
        procedure :: law_plausibility => ligament_plausibility
        procedure :: path => ligament_path
        procedure :: line_tension => ligament_line_tension
        procedure :: line_kind => ligament_kind
        procedure :: scale_items => ligament_items
        procedure :: scale => ligament_scale
        procedure :: stiffen => ligament_stiffen
    end type ligament_family_t

contains

    !> Number of ligaments.
    pure integer function ligament_count(this) result(n)
        class(ligament_family_t), intent(in) :: this   !! the family
        n = 0
        if (allocated(this%items)) n = size(this%items)
    end function ligament_count

    !> Output rows per ligament: tension and length.
    pure integer function ligament_ncomp(this) result(n)
        class(ligament_family_t), intent(in) :: this   !! the family
        n = 2
    end function ligament_ncomp

    !> Slack lengths not given: the neutral lengths.
    pure subroutine ligament_neutral(this, kin)
        class(ligament_family_t), intent(inout) :: this   !! the family; out: slack lengths set
        type(kinematics_t), intent(in) :: kin             !! kinematics of the neutral configuration
        call set_neutral_lengths(kin, this%items)
    end subroutine ligament_neutral

    !> Tensions of every ligament applied to its bodies; stored energy.
    pure subroutine ligament_loads(this, t, kin, x, xd, loads, out, work, energy)
        class(ligament_family_t), intent(in) :: this  !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at (x, xd)
        real(wp), intent(in) :: x(:)                  !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)                 !! their rates [m/s, rad/s]
        type(body_loads_t), intent(inout) :: loads    !! loads, the ligaments' added
        real(wp), intent(inout) :: out(:, :)          !! (2, nl) tension [N], length [m]
        type(family_work_t), intent(inout) :: work    !! scratch (line geometry)
        type(family_energy_t), intent(inout) :: energy !! energy stored, power dissipated and absorbed, the family's added
        associate (gl => work%g)
            call line_geometries(kin, this%items, gl)
            out(1, :) = ligament_tension(this%items, gl%length)
            out(2, :) = gl%length
            call apply_line_tensions(loads, kin, this%items, gl, out(1, :))
            energy%u_elastic = energy%u_elastic + sum(ligament_energy(this%items, gl%length))
        end associate
    end subroutine ligament_loads

    !> One switching function per ligament with l1 > 0 (it becomes taut).
    pure integer function ligament_switch_count(this) result(n)
        class(ligament_family_t), intent(in) :: this   !! the family
        n = count(this%items%l1 > zero)
    end function ligament_switch_count

    !> Length less slack length of every ligament with l1 > 0.
    pure subroutine ligament_switching(this, t, kin, x, sw)
        class(ligament_family_t), intent(in) :: this  !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at x
        real(wp), intent(in) :: x(:)                  !! active coordinates
        real(wp), intent(out) :: sw(:)                !! (switch_count) the switching functions
        type(line_geometry_t) :: gl(size(this%items))
        integer :: e, i
        call line_geometries(kin, this%items, gl)
        i = 0
        do e = 1, size(this%items)
            if (this%items(e)%l1 <= zero) cycle
            i = i + 1
            sw(i) = gl(e)%length - this%items(e)%length0
        end do
    end subroutine ligament_switching

    !> One channel per ligament: its tension.
    pure function ligament_channels(this, tree) result(c)
        class(ligament_family_t), intent(in) :: this  !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree (unused)
        type(family_channel_t), allocatable :: c(:)
        integer :: e
        allocate (c(size(this%items)))
        do e = 1, size(this%items)
            c(e) = family_channel_t(this%items(e)%name, 'N', 'LIGAMENTS', e, 1)
        end do
    end function ligament_channels

    !> /model/elements/ligaments.
    pure function ligament_table(this) result(tab)
        class(ligament_family_t), intent(in) :: this  !! the family
        type(element_table_t) :: tab
        tab = line_table(this, 'ligaments', 'ligament: tension-only band from point a to b')
    end function ligament_table

    !> Ligament e's tension at 2 mm stretch far from the reference model's.
    pure subroutine ligament_plausibility(this, e, warnings)
        class(ligament_family_t), intent(in) :: this  !! the family
        integer, intent(in) :: e                      !! ligament number
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, the ligament's added
        associate (l => this%items(e))
            call check_range('ligament '//trim(l%name)//' tension at 2 mm stretch', &
                             l%l1*2.0e-3_wp + l%l2*(2.0e-3_wp)**l%n, ref_ligament_2mm, 'N', warnings)
        end associate
    end subroutine ligament_plausibility

    !> Ligament e's name and its two ends.
    pure subroutine ligament_path(this, e, name, bodies, points, npt)
        class(ligament_family_t), intent(in) :: this      !! the family
        integer, intent(in) :: e                          !! ligament number
        character(len=12), intent(out) :: name            !! its name
        integer, intent(out) :: bodies(max_via + 2)       !! the ends' bodies
        real(wp), intent(out) :: points(3, max_via + 2)   !! their body-frame positions [m]
        integer, intent(out) :: npt                       !! 2
        name = this%items(e)%name
        call path_points(this%items(e), bodies, points, npt)
    end subroutine ligament_path

    !> Ligament e's tension (eq 10); no damping.
    pure real(wp) function ligament_line_tension(this, e, t, length, rate) result(tension)
        class(ligament_family_t), intent(in) :: this  !! the family
        integer, intent(in) :: e                      !! ligament number
        real(wp), intent(in) :: t                     !! time [s] (unused)
        real(wp), intent(in) :: length                !! length [m]
        real(wp), intent(in) :: rate                  !! its rate [m/s] (unused)
        tension = ligament_tension(this%items(e), length)
    end function ligament_line_tension

    !> 'ligament'.
    pure function ligament_kind(this) result(word)
        class(ligament_family_t), intent(in) :: this  !! the family
        character(len=:), allocatable :: word
        word = 'ligament'
    end function ligament_kind

    !> L1, L2, LENGTH (the law's stretch axis: F(x) becomes F(x/factor)).
    pure subroutine ligament_items(this, items)
        class(ligament_family_t), intent(in) :: this  !! the family
        character(len=item_len), intent(out) :: items(max_family_items)   !! the properties
        items = ''
        items(1:3) = [character(len=item_len) :: 'L1', 'L2', 'LENGTH']
    end subroutine ligament_items

    !> Scale l1 or l2 of every ligament.
    pure subroutine ligament_scale(this, item, factor)
        class(ligament_family_t), intent(inout) :: this   !! the family
        character(len=*), intent(in) :: item              !! L1, L2 or LENGTH
        real(wp), intent(in) :: factor                    !! the factor
        select case (item)
        case ('L1'); this%items%l1 = factor*this%items%l1
        case ('L2'); this%items%l2 = factor*this%items%l2
        case ('LENGTH')      ! F = l1 x + l2 x^n at x/factor: l1/factor, l2/factor^n
            this%items%l1 = this%items%l1/factor
            this%items%l2 = this%items%l2/factor**this%items%n
        end select
    end subroutine ligament_scale

    !> STIFFEN: l1 and l2.
    pure subroutine ligament_stiffen(this, factor)
        class(ligament_family_t), intent(inout) :: this   !! the family
        real(wp), intent(in) :: factor                    !! the factor
        this%items%l1 = factor*this%items%l1
        this%items%l2 = factor*this%items%l2
    end subroutine ligament_stiffen

    !> The ligaments of a model's family slot (a copy; none when the slot holds another family).
    pure function ligaments_of(fam) result(items)
        class(element_family_t), intent(in) :: fam   !! the slot's family
        type(ligament_t), allocatable :: items(:)
        select type (fam)
        type is (ligament_family_t)
            items = fam%items
        class default
            allocate (items(0))
        end select
    end function ligaments_of

    !> A LIGAMENT card: name, bodies, l1, l2, exponent n; the attachment
    !! points and slack length on its continuation card. Kept unless both
    !! ends are on one merged body.
    subroutine ligament_read_card(this, rd, ctx, i, key)
        class(ligament_family_t), intent(inout) :: this   !! the family; out: the ligament added
        type(deck_reader_t), intent(inout) :: rd          !! the deck: card images, located field access, the first error
        type(card_context_t), intent(inout) :: ctx        !! the deck's bodies; out: ninternal counted
        integer, intent(in) :: i                          !! the card's first deck line
        character(len=*), intent(in) :: key               !! the card name (LIGAMENT)
        type(ligament_t) :: g
        logical :: keep
        ! room for every LIGAMENT card, trimmed by end_cards (appending one by one is quadratic)
        if (ctx%needs_room(key, this%nread, size(this%items))) then
            deallocate (this%items)
            allocate (this%items(ctx%ncards(key)))
        end if
        g = ligament_t()
        call line_card(rd, ctx, i, 'ligament', g%line_attach_t, i, 7, keep)
        call rd%real(i, 4, 'l1', 'N/m', g%l1, zero, big_modulus)
        call rd%real(i, 5, 'l2', 'N/m^n', g%l2, zero, 1.0e30_wp)
        call rd%real(i, 6, 'exponent n', '-', g%n, one, 10.0_wp, default=2.0_wp)
        if (.not. keep .or. rd%failed()) return
        this%nread = this%nread + 1
        this%items(this%nread) = g
    end subroutine ligament_read_card

    !> The ligaments read: no room left over.
    subroutine ligament_end_cards(this, rd, ctx)
        class(ligament_family_t), intent(inout) :: this   !! the family; out: items trimmed to the ligaments read
        type(deck_reader_t), intent(inout) :: rd          !! the deck (unused)
        type(card_context_t), intent(inout) :: ctx        !! the deck's cards (unused)
        this%items = this%items(1:this%nread)
    end subroutine ligament_end_cards

    !> The registry's entry of the ligaments: name LIGAMENTS, its card LIGAMENT, and
    !! the family with no elements.
    pure function ligament_registration() result(r)
        type(family_registration_t) :: r
        r = family_registration_t('LIGAMENTS', [family_card_t('LIGAMENT', 0, 1, unique=unique_element)], ligament_empty)
    end function ligament_registration

    !> A family of ligaments with no elements (its arrays allocated with size 0, not
    !! taken from a zero-size array constructor, which gfortran copies into
    !! an unallocated component when the model is copied).
    pure subroutine ligament_empty(slot)
        type(family_slot_t), intent(out) :: slot   !! the slot, holding the empty family
        type(ligament_t), allocatable :: l(:)
        allocate (l(0)); allocate (slot%f, source=ligament_family_t(items=l))
    end subroutine ligament_empty

end module hn_ligament_family
