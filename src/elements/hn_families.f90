!> The registry of element families: the one list of the families, their
!! names (FAMILY, SCALE, STIFFEN, CHANGE ... FAMILY, the sweeps' FAMILY
!! parameters, the listing), the deck cards that make their elements with
!! the continuation cards each takes, and the concrete type of each
!! (`new_family`). A family's number `fam_*` is its place in this list; the
!! model holds one slot per family in this order, and every evaluation
!! visits them in this order (discs, ligaments, muscles, limits, springs,
!! neutral-zone springs, contacts, clamps).
!!
!! The numbers `fam_*` are for src/elements/ alone: elsewhere a family is
!! found by name (`family_index`) or asked through its bindings, and what
!! the deck reader needs of a family's card (its repeat rule, its
!! coordinate fields) is in its entry of `family_cards`.
!!
!! Adding a family: its module (a type extending `element_family_t` of
!! hn_element_family, which reads the family's own cards, `read_card`), one
!! `fam_*` number, one name, its cards in `family_cards`, one case in
!! `new_family`; the card registry hn_cards takes the cards from
!! `family_cards` (docs/architecture.md, "Adding an element family").
module hn_families
    use hn_discs, only: disc_t
    use hn_line_elements, only: ligament_t, muscle_t, spring_t
    use hn_joint_limits, only: joint_limit_t, joint_range_t
    use hn_tables, only: table_t
    use hn_muscle, only: activation_t
    use hn_feedback, only: feedback_t
    use hn_element_family, only: element_family_t, family_slot_t
    use hn_element_cards, only: family_card_t, card_first, card_last, unique_element, unique_name, unique_coordinate
    use hn_disc_family, only: disc_family_t
    use hn_ligament_family, only: ligament_family_t
    use hn_muscle_family, only: muscle_family_t
    use hn_limit_family, only: limit_family_t
    use hn_spring_family, only: spring_family_t
    use hn_nz_family, only: nz_family_t, nz_spring_t
    use hn_contact_family, only: contact_family_t, contact_t
    use hn_clamp_family, only: clamp_family_t, clamp_t
    implicit none
    private

    public :: new_family, family_index, family_names_text, family_card_t, family_cards, card_continuations, &
              family_card_index, cards_with

    !> The families, in evaluation order.
    integer, parameter, public :: fam_discs = 1, fam_ligaments = 2, fam_muscles = 3, &
                                  fam_limits = 4, fam_springs = 5, fam_nz = 6, fam_contacts = 7, &
                                  fam_clamps = 8, nfamilies = 8
    integer, parameter, public :: family_name_len = 9
    !> Their names on FAMILY, SCALE, STIFFEN and CHANGE cards and in the listing.
    character(len=family_name_len), parameter, public :: family_name(nfamilies) = &
        [character(len=family_name_len) :: 'DISCS', 'LIGAMENTS', 'MUSCLES', 'LIMITS', 'SPRINGS', 'NZSPRINGS', 'CONTACTS', 'CLAMPS']

    !> Every card of every family (VIA and ACTIVATE complete the muscles):
    !! key, family, continuation cards, and when it is read (the default
    !! card_in_order: in deck order; ACTIVATE first, the histories HILL cards
    !! name; VIA, FEEDBACK, SPINDLE, GROUP and FIBRE last, on the muscles and histories read before).
    type(family_card_t), parameter :: family_cards(*) = [ &
        family_card_t('DISC', fam_discs, 2, unique=unique_element), &
        family_card_t('LIGAMENT', fam_ligaments, 1, unique=unique_element), &
        family_card_t('MUSCLE', fam_muscles, 1, unique=unique_element), &
        family_card_t('HILL', fam_muscles, 1, unique=unique_element), &
        family_card_t('VIA', fam_muscles, 0, card_last), &
        family_card_t('ACTIVATE', fam_muscles, 1, card_first, unique_name, what='history name'), &
        family_card_t('FEEDBACK', fam_muscles, 0, card_last), &
        family_card_t('SPINDLE', fam_muscles, 0, card_last), &
        family_card_t('GROUP', fam_muscles, 0, card_last), &
        family_card_t('FIBRE', fam_muscles, 0, card_last, unique_name, what='muscle name'), &
        family_card_t('LIMIT', fam_limits, 0, unique=unique_coordinate, coordinate=.true.), &
        family_card_t('ROM', fam_limits, 0, unique=unique_coordinate, coordinate=.true.), &
        family_card_t('SPRING', fam_springs, 1, unique=unique_element), &
        family_card_t('NZSPRING', fam_nz, 0, unique=unique_coordinate, coordinate=.true.), &
        family_card_t('CONTACT', fam_contacts, 2, unique=unique_element), &
        family_card_t('CLAMP', fam_clamps, 1, unique=unique_element)]

contains

    !> A family of kind f with no elements.
    pure subroutine new_family(f, slot)
        integer, intent(in) :: f                    !! family (fam_discs ... fam_clamps)
        type(family_slot_t), intent(out) :: slot    !! the slot, holding an empty family of that kind
        ! the empty arrays are allocated with size 0 (not taken from a
        ! zero-size array constructor, whose result gfortran copies into an
        ! unallocated component when the model is copied)
        type(disc_t), allocatable :: d(:)
        type(ligament_t), allocatable :: l(:)
        type(muscle_t), allocatable :: m(:)
        type(table_t), allocatable :: tb(:)
        type(activation_t), allocatable :: a(:)
        type(feedback_t), allocatable :: fb(:)
        type(joint_limit_t), allocatable :: jl(:)
        type(joint_range_t), allocatable :: jr(:)
        type(spring_t), allocatable :: sp(:)
        type(nz_spring_t), allocatable :: nz(:)
        type(contact_t), allocatable :: ct(:)
        type(clamp_t), allocatable :: cl(:)
        select case (f)
        case (fam_discs)
            allocate (d(0)); allocate (slot%f, source=disc_family_t(items=d))
        case (fam_ligaments)
            allocate (l(0)); allocate (slot%f, source=ligament_family_t(items=l))
        case (fam_muscles)
            allocate (m(0), tb(0), a(0), fb(0))
            allocate (slot%f, source=muscle_family_t(items=m, tables=tb, activations=a, feedbacks=fb))
        case (fam_limits)
            allocate (jl(0), jr(0)); allocate (slot%f, source=limit_family_t(items=jl, ranges=jr))
        case (fam_springs)
            allocate (sp(0)); allocate (slot%f, source=spring_family_t(items=sp))
        case (fam_nz)
            allocate (nz(0)); allocate (slot%f, source=nz_family_t(items=nz))
        case (fam_contacts)
            allocate (ct(0), tb(0)); allocate (slot%f, source=contact_family_t(items=ct, tables=tb))
        case (fam_clamps)
            allocate (cl(0), tb(0)); allocate (slot%f, source=clamp_family_t(items=cl, tables=tb))
        end select
    end subroutine new_family

    !> Number of the family called `name`, 0 when there is none.
    pure integer function family_index(name) result(f)
        character(len=*), intent(in) :: name    !! a family name
        f = 0
        if (len_trim(name) > family_name_len) return
        f = findloc(family_name, name(1:min(len(name), family_name_len)), dim=1)
    end function family_index

    !> The family names as text: "DISCS, LIGAMENTS, ..., NZSPRINGS or CONTACTS".
    pure function family_names_text() result(s)
        character(len=:), allocatable :: s
        integer :: f
        s = trim(family_name(1))
        do f = 2, nfamilies
            s = s//merge(' or ', ',   ', f == nfamilies)
            s = trim(s)//' '//trim(family_name(f))
        end do
    end function family_names_text

    !> Continuation cards of an element card (-1: not a family's card).
    pure integer function card_continuations(key) result(n)
        character(len=*), intent(in) :: key     !! card name
        integer :: k
        n = -1
        k = family_card_index(key)
        if (k > 0) n = family_cards(k)%ncont
    end function card_continuations

    !> The cards of every family of a deck: the registry's, then the
    !! `deck_cards` of `families`, families the registry does not list that
    !! a program brings to its decks (read_case's `families`).
    pure function cards_with(families) result(c)
        type(family_slot_t), intent(in) :: families(:)   !! the families outside the registry
        type(family_card_t), allocatable :: c(:)
        integer :: f
        c = family_cards
        do f = 1, size(families)
            c = [c, families(f)%f%deck_cards()]
        end do
    end function cards_with

    !> Place of card `key` in `family_cards`, 0 when no family of the registry reads it.
    pure integer function family_card_index(key) result(k)
        character(len=*), intent(in) :: key     !! card name
        do k = 1, size(family_cards)
            if (family_cards(k)%key == key) return
        end do
        k = 0
    end function family_card_index

end module hn_families
