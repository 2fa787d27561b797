!> One-run parameter changes: CHANGE cards scale or set a parameter of the
!! case for this run without editing the model deck, with the parameter
!! kinds of a sweep (docs/sweeps.md):
!!
!!   CHANGE  name  FAMILY  family  item           SCALE       factor
!!   CHANGE  name  BODY    body    MASS|INERTIA   SCALE|SET   value
!!   CHANGE  name  FIELDn  card    name-in-F1     SCALE|SET   value   [F2 of the card]
!!
!! A FIELD change addresses its card by the card name, the name in its
!! field F1 and, for cards that F1 alone does not tell apart (NEUTRAL,
!! INITIAL, PRESCRIB and the families' cards that name a coordinate, such
!! as LIMIT and ROM: body and coordinate), the text of its field F2 in the
!! CHANGE card's F7. A change that finds no card, or more than
!! one, names the candidates with their locations.
!!
!! A FIELD change rewrites the field before the cards are interpreted, so
!! that the deck's own checks and units apply to the new value; FAMILY and
!! BODY changes act on the model after every element card. Each change is
!! described in a note (old and new value) for the listing and the result
!! file.
module hn_changes
    use hn_kinds, only: wp, zero, msglen
    use hn_deck_reader, only: deck_reader_t, locate_field, field_text, int_str, nfields, parse_real, upper
    use hn_model, only: model_t, family_items, family_items_text, scale_family, max_family_items
    use hn_families, only: family_index, family_names_text
    use hn_tree, only: tree_build
    implicit none
    private

    public :: change_t, read_changes, apply_field_changes, apply_model_changes, read_param_kind

    !> Parameter kinds, shared with the sweeps' PARAM cards.
    integer, parameter, public :: kind_family = 1   !! a property of every element of a family
    integer, parameter, public :: kind_body = 2     !! a body's mass or inertia
    integer, parameter, public :: kind_field = 3    !! a numeric field of a card
    integer, parameter :: note_len = 160

    !> One CHANGE card.
    type :: change_t
        character(len=10) :: name = ''     !! the change's name (F1)
        integer :: kind = 0                !! kind_family, kind_body or kind_field
        character(len=10) :: target = ''   !! family, body or card name (F3)
        character(len=10) :: item = ''     !! property, or the name in field F1 of the card (F4)
        character(len=10) :: key2 = ''     !! FIELDn: the text of field F2 of the card (F7; blank: any)
        integer :: field = 0               !! field number across the card (FIELDn)
        logical :: set = .false.           !! SET (else SCALE)
        real(wp) :: value = zero           !! factor or new value (F6)
        integer :: line = 0                !! card image of the CHANGE card
    end type change_t

contains

    !> The CHANGE cards at card images `first` of rd, checked field by field.
    subroutine read_changes(rd, first, changes)
        type(deck_reader_t), intent(inout) :: rd          !! the deck (errors located there)
        integer, intent(in) :: first(:)                   !! card images of the CHANGE cards
        type(change_t), allocatable, intent(out) :: changes(:)  !! the changes, in deck order
        character(len=10) :: s
        integer :: k, i
        allocate (changes(size(first)))
        do k = 1, size(first)
            i = first(k)
            changes(k)%line = i
            call rd%name(i, 1, 'change name', changes(k)%name)
            call read_param_kind(rd, i, 2, changes(k)%kind, changes(k)%field)
            if (rd%failed()) return
            call rd%name(i, 3, 'target', changes(k)%target)
            call rd%name(i, 4, 'item', changes(k)%item, optional_blank=changes(k)%kind == kind_field)
            call rd%name(i, 5, 'how', s)
            if (rd%failed()) return
            if (s /= 'SCALE' .and. s /= 'SET') then
                call rd%fail(rd%context(i, 5, 'how')//': found "'//trim(s)//'"; expected SCALE or SET')
                return
            end if
            changes(k)%set = s == 'SET'
            if (changes(k)%set) then
                call rd%real(i, 6, 'new value', 'units of the target', changes(k)%value, -1.0e30_wp, 1.0e30_wp)
            else
                call rd%real(i, 6, 'factor', '-', changes(k)%value, 1.0e-6_wp, 1.0e6_wp)
            end if
            if (rd%failed()) return
            call rd%name(i, 7, 'second key', changes(k)%key2, optional_blank=.true.)
            if (rd%failed()) return
            if (changes(k)%kind /= kind_field .and. len_trim(changes(k)%key2) > 0) then
                call rd%fail(rd%context(i, 7, 'second key')//': found "'//trim(changes(k)%key2)// &
                             '"; expected a blank field (F7 names field F2 of the card a FIELDn change addresses)')
                return
            end if
            if (changes(k)%kind == kind_field .and. changes(k)%target == 'CHANGE') then
                call rd%fail(rd%context(i, 3, 'target')//': found "CHANGE"; expected the card whose field '// &
                             'changes (a CHANGE card cannot change another)')
                return
            end if
        end do
    end subroutine read_changes

    !> The parameter kind in field f of card image i: FAMILY, BODY or FIELDn
    !! (n the field number across the card, 1 to 3*nfields).
    subroutine read_param_kind(rd, i, f, kind, field)
        type(deck_reader_t), intent(inout) :: rd   !! the deck (errors located there)
        integer, intent(in) :: i                   !! card image
        integer, intent(in) :: f                   !! field number on it (1..nfields)
        integer, intent(out) :: kind               !! kind_family, kind_body or kind_field (0 on error)
        integer, intent(out) :: field              !! n of FIELDn (0 for the other kinds)
        character(len=10) :: s
        integer :: ios
        kind = 0
        field = 0
        call rd%name(i, f, 'kind', s)
        if (rd%failed()) return
        if (s == 'FAMILY') then
            kind = kind_family
        else if (s == 'BODY') then
            kind = kind_body
        else if (s(1:5) == 'FIELD') then
            kind = kind_field
            read (s(6:), *, iostat=ios) field
            if (ios /= 0 .or. field < 1 .or. field > 3*nfields) &
                call rd%fail(rd%context(i, f, 'kind')//': found "'//trim(s)//'"; expected FIELDn with n the '// &
                             'field number 1 to 21 (8 to 14 on the first continuation card)')
        else
            call rd%fail(rd%context(i, f, 'kind')//': found "'//trim(s)//'"; expected FAMILY, BODY or FIELDn')
        end if
    end subroutine read_param_kind

    !> Rewrite the fields that FIELD changes name, in rd's card images (the
    !! deck kept for the listing and the result file is not touched).
    subroutine apply_field_changes(rd, changes, notes, coordinate_cards)
        type(deck_reader_t), intent(inout) :: rd                   !! the deck
        type(change_t), intent(in) :: changes(:)                   !! the changes
        character(len=note_len), allocatable, intent(inout) :: notes(:)  !! one line per change made
        character(len=*), intent(in) :: coordinate_cards(:)        !! the element families' cards whose F2 is a coordinate
        integer :: k, nfound, line, c1, c2
        integer, allocatable :: cands(:)
        real(wp) :: old, new
        logical :: ok
        character(len=note_len) :: note
        do k = 1, size(changes)
            associate (c => changes(k), i => changes(k)%line)
                if (c%kind /= kind_field) cycle
                call locate_field(rd%lines(1:rd%nlines), c%target, c%item, c%field, nfound, line, c1, c2, &
                                  name2=c%key2, matches=cands)
                if (nfound /= 1) then
                    call rd%fail(rd%where(i)//' (CHANGE '//trim(c%name)//'): '//not_one(rd, c, cands, coordinate_cards))
                    return
                end if
                if (line == 0) then
                    call rd%fail(rd%where(i)//' (CHANGE '//trim(c%name)//'): the '//trim(c%target)// &
                                 ' card has no continuation card for field '//trim(int_str(c%field)))
                    return
                end if
                call parse_real(rd%lines(line)%text(c1:c2), old, ok)
                if (.not. c%set .and. .not. ok) then
                    call rd%fail(rd%where(i)//' (CHANGE '//trim(c%name)//'): '//rd%where(line)//', columns '// &
                                 trim(int_str(c1))//'-'//trim(int_str(c2))//' holds "'// &
                                 trim(rd%lines(line)%text(c1:c2))//'"; expected a number to SCALE (or SET a value)')
                    return
                end if
                new = c%value
                if (.not. c%set) new = c%value*old
                rd%lines(line)%text(c1:c2) = field_text(new)
                write (note, '(6a)') trim(c%name), ': ', trim(c%target), ' ', trim(c%item), &
                    trim(merge(' '//c%key2, repeat(' ', 11), len_trim(c%key2) > 0))// &
                    ' field F'//trim(int_str(c%field))//' '
                if (ok) then
                    note = trim(note)//' '//trim(adjustl(field_text(old)))//' -> '//trim(adjustl(field_text(new)))
                else
                    note = trim(note)//' blank -> '//trim(adjustl(field_text(new)))
                end if
                notes = [character(len=note_len) :: notes, trim(note)//'  ('//trim(rd%where(i))//')']
            end associate
        end do
    end subroutine apply_field_changes

    !> Why a FIELD change does not address exactly one card: none (with the
    !! cards of that name under other card names or other second keys), or
    !! several, listed with their locations and what would tell them apart.
    function not_one(rd, c, cands, coordinate_cards) result(s)
        type(deck_reader_t), intent(in) :: rd
        type(change_t), intent(in) :: c
        integer, intent(in) :: cands(:)
        character(len=*), intent(in) :: coordinate_cards(:)
        character(len=:), allocatable :: s, what, second
        integer, allocatable :: others(:)
        integer :: j, n, line, c1, c2
        logical :: distinct
        character(len=10), allocatable :: keys(:)
        what = trim(c%target)//' card'
        if (len_trim(c%item) > 0) what = what//'s named '//trim(c%item)
        if (len_trim(c%item) == 0) what = what//'s'
        if (len_trim(c%key2) > 0) what = what//' with '//trim(c%key2)//' in F2'
        second = 'field F2 of the card'
        if (any(c%target == [character(len=10) :: 'NEUTRAL', 'INITIAL', 'PRESCRIB']) .or. &
            any(c%target == coordinate_cards)) second = 'the coordinate'
        if (size(cands) == 0) then
            s = 'found 0 '//what//' in the deck; expected exactly one'
            if (len_trim(c%key2) > 0) then
                ! that card name and F1, other F2s
                call locate_field(rd%lines(1:rd%nlines), c%target, c%item, c%field, n, line, c1, c2, matches=others)
                if (n > 0) s = s//' (the '//trim(c%target)//' cards named '//trim(c%item)//': '// &
                               candidates(rd, others, 2)//'; '//second//' goes in F7)'
            else if (len_trim(c%item) > 0) then
                ! other cards of that name in F1
                allocate (others(0))
                do j = 1, rd%nlines
                    if (any(upper(rd%lines(j)%text(1:8)) == [character(len=8) :: '', 'CHANGE'])) cycle
                    if (upper(adjustl(rd%lines(j)%text(11:20))) == c%item) others = [others, j]
                end do
                if (size(others) > 0) s = s//' (cards named '//trim(c%item)//': '//candidates(rd, others, 0)//')'
            end if
            return
        end if
        s = 'found '//trim(int_str(size(cands)))//' '//what//' ('
        if (len_trim(c%item) > 0) then
            s = s//candidates(rd, cands, 2)//'); expected '
        else
            s = s//candidates(rd, cands, 1)//'); expected '
        end if
        if (len_trim(c%item) == 0) then
            s = s//'the name in field F1 of the card in F4'
            return
        end if
        keys = f2(rd, cands)
        distinct = len_trim(c%key2) == 0
        do j = 2, size(cands)
            if (any(keys(1:j - 1) == keys(j))) distinct = .false.
        end do
        if (distinct) then
            s = s//second//' too, in F7: '//trim(rd%lines(c%line)%text(1:70)//keys(1))
        else
            s = s//'one card: these cards are not told apart by the card name, F1 and F2 (cards that combine '// &
                'cannot be changed one by one)'
        end if
    end function not_one

    !> Field F2 of card images idx, upper case, left-adjusted.
    pure function f2(rd, idx) result(t)
        type(deck_reader_t), intent(in) :: rd
        integer, intent(in) :: idx(:)
        character(len=10) :: t(size(idx))
        integer :: j
        do j = 1, size(idx)
            t(j) = upper(adjustl(rd%lines(idx(j))%text(21:30)))
        end do
    end function f2

    !> The card images idx as "stdin line 290 RX, line 291 RY, ...": the
    !! place in full when it differs from the one before, with its fields F2
    !! (show = 2), F1 and F2 (show = 1) or its card name (show = 0); at most 6.
    function candidates(rd, idx, show) result(s)
        type(deck_reader_t), intent(in) :: rd
        integer, intent(in) :: idx(:), show
        character(len=:), allocatable :: s
        integer :: j, i, p
        s = ''
        do j = 1, min(size(idx), 6)
            i = idx(j)
            if (j > 1) s = s//', '
            if (show == 0) s = s//'the '//trim(upper(rd%lines(i)%text(1:8)))//' card at '
            if (j > 1) then
                p = idx(j - 1)
                if (rd%lines(p)%source == rd%lines(i)%source .and. rd%lines(p)%via == rd%lines(i)%via .and. &
                    show /= 0) then
                    s = s//'line '//trim(int_str(rd%lines(i)%line))
                else
                    s = s//rd%where(i)
                end if
            else
                s = s//rd%where(i)
            end if
            if (show == 1) s = s//' '//trim(upper(adjustl(rd%lines(i)%text(11:20))))
            if (show >= 1) s = s//' '//trim(upper(adjustl(rd%lines(i)%text(21:30))))
        end do
        if (size(idx) > 6) s = s//', ... ('//trim(int_str(size(idx)))//' in all)'
    end function candidates

    !> Apply the FAMILY and BODY changes to the model: family properties
    !! scaled, body masses and inertias scaled or set (the tree's derived
    !! tables rebuilt).
    subroutine apply_model_changes(rd, changes, model, notes)
        type(deck_reader_t), intent(inout) :: rd                   !! the deck (errors located there)
        type(change_t), intent(in) :: changes(:)                   !! the changes
        type(model_t), intent(inout) :: model                      !! the model changed
        character(len=note_len), allocatable, intent(inout) :: notes(:)  !! one line per change made
        character(len=10) :: items(max_family_items)
        character(len=note_len) :: note
        character(len=msglen) :: msg
        integer :: k, fam, kb, stat
        real(wp) :: old
        logical :: rebuild
        rebuild = .false.
        do k = 1, size(changes)
            associate (c => changes(k), i => changes(k)%line)
                select case (c%kind)
                case (kind_family)
                    fam = family_index(c%target)
                    if (fam == 0) then
                        call rd%fail(rd%context(i, 3, 'target')//': found "'//trim(c%target)// &
                                     '"; expected '//family_names_text())
                        return
                    end if
                    items = family_items(fam)
                    if (.not. any(items == c%item .and. len_trim(items) > 0)) then
                        call rd%fail(rd%context(i, 4, 'item')//': found "'//trim(c%item)//'"; expected '// &
                                     family_items_text(fam)//' for '//trim(c%target))
                        return
                    end if
                    if (c%set) then
                        call rd%fail(rd%context(i, 5, 'how')//': found "SET"; a FAMILY change scales every '// &
                                     'element of the family: expected SCALE')
                        return
                    end if
                    call scale_family(model, fam, c%item, c%value)
                    write (note, '(5a)') trim(c%name), ': every element of ', trim(c%target), ', ', trim(c%item)
                    note = trim(note)//' x '//trim(adjustl(field_text(c%value)))
                case (kind_body)
                    kb = findloc(model%tree%name, c%target, dim=1)
                    if (kb == 0) then
                        call rd%fail(rd%context(i, 3, 'target')//': found "'//trim(c%target)// &
                                     '"; expected a body of the deck (after its MERGE cards)')
                        return
                    end if
                    if (c%item == 'MASS') then
                        old = model%tree%mass(kb)
                        model%tree%mass(kb) = merge(c%value, c%value*old, c%set)
                        if (.not. (model%tree%mass(kb) > zero)) then
                            call rd%fail(rd%context(i, 6, 'new value')//': gives a mass of '// &
                                         trim(adjustl(field_text(model%tree%mass(kb))))//' kg; expected a positive mass')
                            return
                        end if
                        note = trim(c%name)//': mass of '//trim(c%target)//' '//trim(adjustl(field_text(old)))// &
                               ' -> '//trim(adjustl(field_text(model%tree%mass(kb))))//' kg'
                    else if (c%item == 'INERTIA') then
                        if (c%set) then
                            call rd%fail(rd%context(i, 5, 'how')//': found "SET"; an inertia matrix is scaled '// &
                                         '(SET it on the BODY card): expected SCALE')
                            return
                        end if
                        model%tree%inertia(:, :, kb) = c%value*model%tree%inertia(:, :, kb)
                        note = trim(c%name)//': inertia of '//trim(c%target)//' x '//trim(adjustl(field_text(c%value)))
                    else
                        call rd%fail(rd%context(i, 4, 'item')//': found "'//trim(c%item)//'"; expected MASS or INERTIA')
                        return
                    end if
                    rebuild = .true.
                case default
                    cycle
                end select
                notes = [character(len=note_len) :: notes, trim(note)//'  ('//trim(rd%where(i))//')']
            end associate
        end do
        if (rebuild) then
            call tree_build(model%tree, stat, msg)
            if (stat /= 0) call rd%fail(rd%where(changes(1)%line)//' (CHANGE cards): '//trim(msg))
        end if
    end subroutine apply_model_changes

end module hn_changes
