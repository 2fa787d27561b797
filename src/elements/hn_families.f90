!> The registry of element families: the one list of the families, one
!! line per family (`registered_families`), each line the entry its module
!! exports (hn_family_registration: the family's name, the deck cards that
!! make its elements with the continuation cards each takes, and how to make
!! it empty). A family's number is its place in this list; the model holds
!! one slot per family in this order, and every evaluation visits them in
!! this order (discs, ligaments, muscles, limits, springs, neutral-zone
!! springs, contacts, clamps, facets).
!!
!! Elsewhere a family is found by name (`family_index`) or asked through its
!! bindings, and what the deck reader needs of a family's card (its repeat
!! rule, its coordinate fields) is in its entry's cards (`family_cards`).
!!
!! Adding a family: its module (a type extending `element_family_t` of
!! hn_element_family, which reads the family's own cards, `read_card`, and
!! a function returning its `family_registration_t`), and one line in
!! `registered_families` with the `use` of that function; the card
!! registry hn_cards takes the cards from `family_cards`
!! (docs/architecture.md, "Adding an element family").
module hn_families
    use hn_element_family, only: family_slot_t
    use hn_element_cards, only: family_card_t
    use hn_family_registration, only: family_registration_t, family_name_len
    use hn_disc_family, only: disc_registration
    use hn_ligament_family, only: ligament_registration
    use hn_muscle_family, only: muscle_registration
    use hn_limit_family, only: limit_registration
    use hn_spring_family, only: spring_registration
    use hn_nz_family, only: nz_registration
    use hn_contact_family, only: contact_registration
    use hn_clamp_family, only: clamp_registration
    use hn_facet_family, only: facet_registration
    implicit none
    private

    public :: family_registration_t, family_card_t, family_name_len
    public :: registered_families, nfamilies, family_name, family_names, new_family, family_index, family_names_text
    public :: family_cards, card_continuations, family_card_index, cards_with

contains

    !> The registry: one line per family, in evaluation order; the cards of
    !! each carry the family's place.
    pure function registered_families() result(r)
        type(family_registration_t), allocatable :: r(:)
        integer :: f
        r = [disc_registration(), &
             ligament_registration(), &
             muscle_registration(), &
             limit_registration(), &
             spring_registration(), &
             nz_registration(), &
             contact_registration(), &
             clamp_registration(), &
             facet_registration()]
        do f = 1, size(r)
            r(f)%cards%family = f
        end do
    end function registered_families

    !> Number of families of the registry.
    pure integer function nfamilies() result(n)
        n = size(registered_families())
    end function nfamilies

    !> Name of family f of the registry (on FAMILY, SCALE, STIFFEN and CHANGE cards and in the listing).
    pure function family_name(f) result(name)
        integer, intent(in) :: f                    !! family (1 .. nfamilies())
        character(len=family_name_len) :: name
        type(family_registration_t), allocatable :: r(:)
        r = registered_families()
        name = r(f)%name
    end function family_name

    !> The names of the registry's families, in its order.
    pure function family_names() result(names)
        character(len=family_name_len), allocatable :: names(:)
        type(family_registration_t), allocatable :: r(:)
        r = registered_families()
        names = r%name
    end function family_names

    !> A family of the registry's kind f with no elements.
    pure subroutine new_family(f, slot)
        integer, intent(in) :: f                    !! family (1 .. nfamilies())
        type(family_slot_t), intent(out) :: slot    !! the slot, holding an empty family of that kind
        type(family_registration_t), allocatable :: r(:)
        r = registered_families()
        call r(f)%empty(slot)
    end subroutine new_family

    !> Number of the family called `name`, 0 when there is none.
    pure integer function family_index(name) result(f)
        character(len=*), intent(in) :: name    !! a family name
        f = 0
        if (len_trim(name) > family_name_len) return
        f = findloc(family_names(), name(1:min(len(name), family_name_len)), dim=1)
    end function family_index

    !> The family names as text: "DISCS, LIGAMENTS, ..., NZSPRINGS or CONTACTS".
    pure function family_names_text() result(s)
        character(len=:), allocatable :: s
        character(len=family_name_len), allocatable :: names(:)
        integer :: f
        names = family_names()
        s = trim(names(1))
        do f = 2, size(names)
            s = s//merge(' or ', ',   ', f == size(names))
            s = trim(s)//' '//trim(names(f))
        end do
    end function family_names_text

    !> Every card of every family of the registry, in its order: key,
    !! family, continuation cards, when it is read, its repeat rule.
    pure function family_cards() result(c)
        type(family_card_t), allocatable :: c(:)
        type(family_registration_t), allocatable :: r(:)
        integer :: f
        r = registered_families()
        allocate (c(0))
        do f = 1, size(r)
            c = [c, r(f)%cards]
        end do
    end function family_cards

    !> Continuation cards of an element card (-1: not a family's card).
    pure integer function card_continuations(key) result(n)
        character(len=*), intent(in) :: key     !! card name
        type(family_registration_t), allocatable :: r(:)
        integer :: f, k
        n = -1
        r = registered_families()
        do f = 1, size(r)
            do k = 1, size(r(f)%cards)
                if (r(f)%cards(k)%key /= key) cycle
                n = r(f)%cards(k)%ncont
                return
            end do
        end do
    end function card_continuations

    !> The cards of every family of a deck, each with its family's number:
    !! the registry's, then those of `families`, entries of families the
    !! registry does not list that a program brings to its decks (read_case's
    !! `families`), numbered after the registry's in their order.
    pure function cards_with(families) result(c)
        type(family_registration_t), intent(in) :: families(:)   !! the families outside the registry
        type(family_card_t), allocatable :: c(:), more(:)
        integer :: f, n
        c = family_cards()
        n = nfamilies()
        do f = 1, size(families)
            more = families(f)%cards
            more%family = n + f
            c = [c, more]
        end do
    end function cards_with

    !> Place of card `key` in `family_cards()`, 0 when no family of the registry reads it.
    pure integer function family_card_index(key) result(k)
        character(len=*), intent(in) :: key     !! card name
        type(family_card_t), allocatable :: c(:)
        c = family_cards()
        do k = 1, size(c)
            if (c(k)%key == key) return
        end do
        k = 0
    end function family_card_index

end module hn_families
