!> One element family as the registry (hn_families) lists it: its name (on
!! FAMILY, SCALE, STIFFEN and CHANGE ... FAMILY cards, the sweeps' FAMILY
!! parameters and the listing), the deck cards that make its elements, and
!! how to make it with no elements. Each family module exports a function
!! returning its entry (`disc_registration`, ...); the registry is the list
!! of those calls, one line per family, in evaluation order.
module hn_family_registration
    use hn_element_family, only: family_slot_t
    use hn_element_cards, only: family_card_t
    implicit none
    private

    public :: family_registration_t, empty_family_sub

    integer, parameter, public :: family_name_len = 9   !! longest family name

    !> A family's entry in the registry.
    type :: family_registration_t
        character(len=family_name_len) :: name = ''   !! the family's name (DISCS, LIGAMENTS, ...)
        !> the cards that make its elements, with their continuation cards,
        !! reading order and repeat rule (the `family` of each: 0 here, the
        !! family's place once the registry lists it)
        type(family_card_t), allocatable :: cards(:)
        procedure(empty_family_sub), pointer, nopass :: empty => null()   !! puts the family, empty, into a slot
    end type family_registration_t

    abstract interface
        !> Put a family of the entry's kind with no elements into `slot`
        !! (its arrays allocated with size 0).
        pure subroutine empty_family_sub(slot)
            import :: family_slot_t
            type(family_slot_t), intent(out) :: slot   !! the slot, holding the empty family
        end subroutine empty_family_sub
    end interface

end module hn_family_registration
