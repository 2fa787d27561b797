!> The element cards of a deck: the cards of the element families, each
!! read by its family (`read_card` of hn_element_family; which family reads
!! which card, and when, is the registry's, hn_families `family_cards`, or
!! the `deck_cards` of a family added to the model in code), and SCALE and
!! FAMILY, which act on a family (`element_cards`). No family is named here.
module hn_deck_elements
    use hn_kinds, only: wp
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t
    use hn_model, only: model_t, family_items, family_items_text, scale_family, max_family_items
    use hn_families, only: family_name, family_names, family_index, family_cards
    use hn_element_cards, only: card_context_t, family_card_t, card_first, card_in_order, card_last
    use hn_deck_state, only: deck_state_t, add_scene_note, family_ref, join
    implicit none
    private

    public :: element_cards, scale_card, family_card

contains

    !> The element cards: each family's cards read by the family, in the
    !! order of the registry (cards read first, the cards in deck order with
    !! the FAMILY cards, cards read last), then what each family does after
    !! its cards, then the SCALE cards. Elements are moved onto merged
    !! bodies; an element inside one merged body, or a joint damper on a
    !! locked or merged coordinate, is dropped (a scene note says how many).
    subroutine element_cards(rd, st, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(deck_state_t), intent(in) :: st  !! the deck's cards, bodies (names, where each went) and tables
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        type(card_context_t) :: ctx
        integer :: k, i, f, order, pass
        character(len=100) :: note
        ctx%deck_state_t = st
        ctx%tree = cs%model%tree
        ctx%prescribed = cs%model%prescribed
        ctx%motion = cs%model%motion
        ctx%t_start = cs%t_start
        ctx%t_end = cs%t_end
        allocate (ctx%notes(0))
        do pass = card_first, card_last
            do k = 1, size(st%cards)
                i = st%cards(k)%first
                call card_family(cs%model, st, st%cards(k)%key, f, order)
                if (f > 0 .and. order == pass) then
                    call cs%model%family(f)%f%read_card(rd, ctx, i, st%cards(k)%key)
                else if (f == 0 .and. pass == card_in_order .and. st%cards(k)%key == 'FAMILY') then
                    call family_card(rd, i, cs)
                end if
                if (rd%failed()) return
            end do
        end do
        if (ctx%ninternal > 0) then
            write (note, '(i0,a)') ctx%ninternal, ' ELEMENTS DROPPED: BOTH ENDS ON ONE MERGED BODY'
            call add_scene_note(cs, note)
        end if
        do f = 1, size(cs%model%family)
            call cs%model%family(f)%f%end_cards(rd, ctx)
            if (rd%failed()) return
        end do
        do k = 1, size(ctx%notes)
            call add_scene_note(cs, ctx%notes(k))
        end do
        do k = 1, size(st%cards)
            if (st%cards(k)%key == 'SCALE') call scale_card(rd, st%cards(k)%first, cs)
            if (rd%failed()) return
        end do
    end subroutine element_cards

    !> The family that reads card `key` and when (card_first, card_in_order,
    !! card_last): the deck's family cards (`fcards`) when it has them, else
    !! the registry's, else a family of the model whose deck_cards list it;
    !! f = 0 when no family reads it.
    subroutine card_family(model, st, key, f, order)
        type(model_t), intent(in) :: model
        type(deck_state_t), intent(in) :: st
        character(len=*), intent(in) :: key
        integer, intent(out) :: f, order
        type(family_card_t), allocatable :: own(:)
        integer :: k
        order = 0
        if (allocated(st%fcards)) then
            own = st%fcards
        else
            own = family_cards()
        end if
        do k = 1, size(own)
            if (own(k)%key /= key) cycle
            f = own(k)%family
            order = own(k)%order
            return
        end do
        f = 0
        if (allocated(st%fcards)) return
        do f = 1, size(model%family)
            own = model%family(f)%f%deck_cards()
            do k = 1, size(own)
                if (own(k)%key /= key) cycle
                order = own(k)%order
                return
            end do
        end do
        f = 0
    end subroutine card_family

    !> SCALE name family item factor: multiply one property of every element
    !! of a family (the items of a sweep's FAMILY parameters), after every
    !! element card; the named factors a calibration fits (FIELD4 SCALE name).
    subroutine scale_card(rd, i, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        character(len=10) :: s, item, items(max_family_items)
        integer :: fam
        real(wp) :: factor
        call rd%name(i, 1, 'factor name', s)
        call rd%name(i, 2, 'element family', s)
        fam = family_ref(rd, i, s)
        if (rd%failed()) return
        call rd%name(i, 3, 'item', item)
        items = family_items(fam)
        if (.not. rd%failed() .and. .not. any(items == item .and. len_trim(items) > 0)) then
            call rd%fail(rd%context(i, 3, 'item')//': found "'//trim(item)//'"; expected '//family_items_text(fam))
            return
        end if
        call rd%real(i, 4, 'factor', '-', factor, 1.0e-6_wp, 1.0e6_wp)
        if (rd%failed()) return
        call scale_family(cs%model, fam, item, factor)
    end subroutine scale_card

    !> FAMILY name ON|OFF: switch an element family.
    subroutine family_card(rd, i, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        integer :: fam
        character(len=10) :: s
        character(len=100) :: note
        call rd%name(i, 1, 'element family', s)
        if (rd%failed()) return
        fam = family_index(s)
        if (fam == 0) then
            call rd%fail(rd%context(i, 1, 'element family')//': found "'// &
                         trim(s)//'"; expected one of '//join(family_names()))
            return
        end if
        call rd%name(i, 2, 'ON or OFF', s)
        if (s /= 'ON' .and. s /= 'OFF' .and. .not. rd%failed()) then
            call rd%fail(rd%context(i, 2, 'ON or OFF')//': found "'//trim(s)// &
                         '"; expected ON or OFF')
            return
        end if
        cs%model%family_on(fam) = s == 'ON'
        if (s == 'OFF') then
            note = 'FAMILY '//trim(family_name(fam))//' OFF'
            call add_scene_note(cs, note)
        end if
    end subroutine family_card

end module hn_deck_elements
