!> What the card groups of the deck reader share: the grouping of deck
!! lines into cards (`group_cards`, by the card engine on the card registry
!! hn_cards), the only card of a kind (`single`), scene notes, and the located references
!! of one card to bodies, coordinates and families. The types the groups
!! pass along (`deck_state_t`: the cards `card_t`, where each deck body
!! went `body_map_t`, the named tables `named_table_t`) and the references
!! an element family needs to read its own cards live one layer down, in
!! hn_element_cards, and are re-exported here. The modules hn_deck_<group>
!! read their cards with these and the field access of hn_deck_reader.
module hn_deck_state
    use hn_kinds, only: wp
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t
    use hn_cards, only: case_deck_format, max_table_points
    use hn_card_engine, only: group_deck_cards
    use hn_families, only: family_names, family_index
    use hn_element_cards, only: deck_state_t, card_t, body_map_t, named_table_t, family_card_t, coord_names, big_length, &
                                big_modulus, body_ref, coord_ref, table_ref, active_coordinate, locked_error, unit_of, &
                                unit_factor, unit_limit
    implicit none
    private

    public :: deck_state_t, coord_names, big_length, big_modulus, max_table_points, tiny_value, card_t, body_map_t, named_table_t, &
              group_cards, single, add_scene_note, k_old, locked_error, active_coordinate, family_ref, body_ref, coord_ref, &
              table_ref, unit_of, unit_factor, unit_limit, join, real_str

    real(wp), parameter :: tiny_value = 1.0e-30_wp  !! a table whose values are all below this is zero in effect

contains

    !> Split the lines into cards by the card engine (hn_card_engine) on the
    !! case deck's format (the card registry hn_cards): names, continuation
    !! counts, the cards a deck holds once, and that TITLE comes first and
    !! CONTROL is there (a deck; not a few card images for one card group,
    !! title_first false). `more` are the cards of the deck's element
    !! families, the registry's and those it does not list (families a
    !! model built in code holds, model_add_family: their `deck_cards`).
    subroutine group_cards(rd, cards, title_first, more)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), allocatable, intent(out) :: cards(:)  !! the cards, each with the count of its continuation cards
        logical, intent(in), optional :: title_first  !! a whole deck: TITLE first, CONTROL there (default: yes)
        type(family_card_t), intent(in), optional :: more(:)  !! the deck's family cards (default: the registry's)
        call group_deck_cards(rd, case_deck_format(more), cards, title_first)
    end subroutine group_cards

    !> Index of the last card `key` (the card engine refused a second card
    !! of a kind the registry, hn_cards, holds once); 0 when absent.
    pure integer function single(cards, key) result(ic)
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        character(len=*), intent(in) :: key  !! the card name
        do ic = size(cards), 1, -1
            if (cards(ic)%key == key) return
        end do
        ic = 0
    end function single

    !> Append a line to the scene notes of the listing.
    subroutine add_scene_note(cs, text)
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        character(len=*), intent(in) :: text  !! the note (at most 100 characters)
        character(len=100), allocatable :: tmp(:)
        integer :: n
        n = size(cs%scene)
        allocate (tmp(n + 1))
        tmp(1:n) = cs%scene
        tmp(n + 1) = text
        call move_alloc(tmp, cs%scene)
    end subroutine add_scene_note

    !> Old (deck) body number of field F1 of line i.
    integer function k_old(rd, i, bnames) result(k)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        character(len=10), intent(in) :: bnames(:)  !! the names of the deck's bodies, in deck order
        k = body_ref(rd, i, 1, 'body', bnames, .false.)
    end function k_old

    !> Element family named s in field F2 of line i (an error when unknown).
    integer function family_ref(rd, i, s) result(fam)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        character(len=*), intent(in) :: s  !! the family name found on the card
        fam = 0
        if (rd%failed()) return
        fam = family_index(s)
        if (fam == 0) call rd%fail(rd%context(i, 2, 'element family')//': found "'//trim(s)//'"; expected one of '// &
                                   join(family_names()))
    end function family_ref

    pure function join(list) result(s)
        character(len=*), intent(in) :: list(:)  !! the words
        character(len=:), allocatable :: s
        integer :: k
        s = trim(list(1))
        do k = 2, size(list)
            s = s//' '//trim(list(k))
        end do
    end function join

    pure function real_str(v) result(s)
        real(wp), intent(in) :: v  !! the value
        character(len=24) :: s
        write (s, '(g0.6)') v
    end function real_str

end module hn_deck_state
