!> What the card groups of the deck reader share: the grouping of deck
!! lines into cards (`group_cards`, by the card registry hn_cards), the
!! only card of a kind (`single`), scene notes, and the located references
!! of one card to bodies, coordinates and families. The types the groups
!! pass along (`deck_state_t`: the cards `card_t`, where each deck body
!! went `body_map_t`, the named tables `named_table_t`) and the references
!! an element family needs to read its own cards live one layer down, in
!! hn_element_cards, and are re-exported here. The modules hn_deck_<group>
!! read their cards with these and the field access of hn_deck_reader.
module hn_deck_state
    use hn_kinds, only: wp
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t, int_str, upper
    use hn_cards, only: card_known, card_ncont, card_repeats
    use hn_families, only: family_names, family_index
    use hn_element_cards, only: deck_state_t, card_t, body_map_t, named_table_t, family_card_t, coord_names, big_length, &
                                ncont_optional, continued, &
                                big_modulus, body_ref, coord_ref, table_ref, active_coordinate, locked_error, unit_of, &
                                unit_factor, unit_limit
    implicit none
    private

    public :: deck_state_t, coord_names, big_length, big_modulus, max_table_points, tiny_value, card_t, body_map_t, named_table_t, &
              group_cards, single, add_scene_note, k_old, locked_error, active_coordinate, family_ref, body_ref, coord_ref, &
              table_ref, unit_of, unit_factor, unit_limit, join, real_str

    integer, parameter :: max_table_points = 100000 !! points of one TABLE
    real(wp), parameter :: tiny_value = 1.0e-30_wp  !! a table whose values are all below this is zero in effect

contains

    !> Split the lines into cards, checking names (the card registry),
    !! continuation counts and that TITLE comes first (a deck; not a few
    !! card images for one card group, title_first false). `more` are the
    !! cards of element families the registry does not list (families a
    !! model built in code holds, model_add_family: their `deck_cards`).
    subroutine group_cards(rd, cards, title_first, more)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), allocatable, intent(out) :: cards(:)  !! the cards, each with the count of its continuation cards
        logical, intent(in), optional :: title_first  !! refuse a first card other than TITLE (default: yes)
        type(family_card_t), intent(in), optional :: more(:)  !! cards of families outside the registry
        integer :: i, nc, need, npts, ios, kmore
        character(len=8) :: key
        character(len=10) :: s
        logical :: title
        title = .true.
        if (present(title_first)) title = title_first
        allocate (cards(rd%nlines))
        nc = 0
        i = 1
        do while (i <= rd%nlines)
            key = rd%key(i)
            if (len_trim(rd%lines(i)%text(1:10)) == 0) then
                call rd%fail(rd%where(i)//', columns 1-8: found a continuation card (blank card name) '// &
                             'where a new card was expected; too many continuation cards for the card above?')
                return
            end if
            if (rd%lines(i)%text(9:10) /= '  ') then
                call rd%fail(rd%where(i)//', columns 9-10: found "'//rd%lines(i)%text(9:10)// &
                             '"; expected blanks after the card name (fields start in column 11)')
                return
            end if
            if (key == 'END') exit
            kmore = 0
            if (present(more)) then
                do kmore = size(more), 1, -1       ! (a loop: no temporary of the key component)
                    if (more(kmore)%key == key) exit
                end do
            end if
            if (.not. card_known(key) .and. kmore == 0) then
                call rd%fail(rd%where(i)//', columns 1-8: found unknown card "'//trim(key)// &
                             '"; expected one of TITLE CONTROL BODY JOINT ... (docs/deck-format.md)')
                return
            end if
            if (nc == 0 .and. key /= 'TITLE' .and. title) then
                call rd%fail(rd%where(i)//', columns 1-8: found "'//trim(key)//'"; expected a TITLE card first')
                return
            end if
            need = card_ncont(key)
            if (kmore > 0) need = more(kmore)%ncont
            if (need == ncont_optional) need = merge(1, 0, continued(rd, i))
            if (need < 0) then
                s = rd%raw(i, 2)
                read (s, *, iostat=ios) npts
                if (ios /= 0 .or. npts < 1 .or. npts > max_table_points) then
                    call rd%int(i, 2, 'number of points', npts, 1, max_table_points)
                    if (.not. rd%failed()) call rd%fail(rd%where(i)//': bad TABLE point count')
                    return
                end if
                need = (npts + 2)/3
                if (upper(adjustl(rd%raw(i, 5))) == 'CSV') need = 1     ! the file name card
            end if
            nc = nc + 1
            cards(nc)%key = key
            cards(nc)%first = i
            cards(nc)%ncont = need
            if (i + need > rd%nlines) then
                call rd%fail(rd%where(i)//' ('//trim(key)//' card): the deck ends before its '// &
                             trim(int_str(need))//' continuation card(s)')
                return
            end if
            do i = i + 1, i + need
                if (len_trim(rd%lines(i)%text(1:10)) /= 0) then
                    call rd%fail(rd%where(i)//', columns 1-10: found "'//trim(rd%lines(i)%text(1:10))// &
                                 '"; expected a continuation card of the '//trim(key)// &
                                 ' card above (columns 1-10 blank)')
                    return
                end if
            end do
        end do
        cards = cards(1:nc)
    end subroutine group_cards

    !> Index of the only card of a type; 0 when absent; error when repeated
    !! (a card the registry, hn_cards, lets repeat: the last one).
    integer function single(rd, cards, key, required) result(ic)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        character(len=*), intent(in) :: key  !! the card name
        logical, intent(in) :: required  !! whether the deck must have one
        integer :: k
        ic = 0
        do k = 1, size(cards)
            if (cards(k)%key /= key) cycle
            if (ic /= 0 .and. .not. card_repeats(key)) then
                call rd%fail(rd%where(cards(k)%first)//', columns 1-8: found a second '//key// &
                             ' card; expected only one (the first is at '//rd%where(cards(ic)%first)//')')
                return
            end if
            ic = k
        end do
        if (ic == 0 .and. required) call rd%fail(rd%top//': the deck has no '//key//' card; expected one')
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
