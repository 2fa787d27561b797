!> The card engine of the fixed-format decks (the case deck, the sweep
!! deck, the calibration deck). A deck's cards are a table, its
!! `deck_format_t`: one `deck_card_t` per card name with its continuation
!! cards, how many of it a deck may hold and the procedure that reads it
!! (a procedure pointer of the abstract interface `card_handler`, so a
!! table naming a handler that does not exist, or has another interface,
!! does not compile). The engine splits a deck's card images into cards
!! (`group_deck_cards`) with the checks every deck shares, each refused at
!! its line and columns: a blank card name where a card is expected, text
!! in columns 9-10 (fields start in column 11), an unknown card (naming
!! the cards expected), a first card other than TITLE, continuation cards
!! missing or not blank in columns 1-10, a card given more often than its
!! table entry allows (naming the first), a required card missing. Then
!! `read_deck_cards` calls each card's handler in deck order. END stops
!! the reading; INCLUDE is the reader's (hn_deck_reader).
!!
!! A deck's reading state extends `card_deck_t` (the reader `rd` and what
!! its handlers fill), and each handler takes it as `class(card_deck_t)`
!! and selects its own type.
module hn_card_engine
    use hn_deck_reader, only: deck_reader_t, int_str
    implicit none
    private

    public :: card_t, deck_card_t, deck_format_t, card_deck_t, card_handler, card_counter
    public :: group_deck_cards, read_deck_cards, continued

    !> Continuation counts that are not fixed: counted from the card itself
    !! by its entry's `count` (a TABLE's points); one continuation card when
    !! the next deck line's columns 1-10 are blank, none otherwise.
    integer, parameter, public :: ncont_counted = -1, ncont_optional = -2

    !> How many cards of a name a deck may hold: any number; at most one;
    !! exactly one (a whole deck without one is refused); at most one in each
    !! file of the deck (the deck itself and each INCLUDEd file).
    integer, parameter, public :: any_times = 0, at_most_once = 1, exactly_once = 2, once_per_file = 3

    integer, parameter :: max_list = 240   !! longest list of card names in a message

    !> One card with its continuation cards: deck lines first .. first+ncont.
    type :: card_t
        character(len=8) :: key = ''
        integer :: first = 0      !! its deck line
        integer :: ncont = 0      !! its continuation cards
        integer :: entry = 0      !! its entry in the deck's table (deck_format_t%cards)
    end type card_t

    !> A deck being read: its card images with the located field access and
    !! the first error; a deck extends it with what its handlers fill.
    type, abstract :: card_deck_t
        type(deck_reader_t) :: rd   !! the deck: card images, located field access, the first error
    end type card_deck_t

    abstract interface
        !> Read one card of the deck into the deck's reading state.
        subroutine card_handler(deck, i)
            import :: card_deck_t
            class(card_deck_t), intent(inout) :: deck   !! the deck being read (its own extension of card_deck_t)
            integer, intent(in) :: i                    !! the card's deck line
        end subroutine card_handler

        !> The continuation cards of the card at deck line i, from its fields.
        subroutine card_counter(rd, i, n)
            import :: deck_reader_t
            type(deck_reader_t), intent(inout) :: rd    !! the deck; a located error when the count is bad
            integer, intent(in) :: i                    !! the card's deck line
            integer, intent(out) :: n                   !! its continuation cards
        end subroutine card_counter
    end interface

    !> One card of a deck's table: its name, its continuation cards, how
    !! many of it a deck may hold, the procedure that reads it (null():
    !! none, the deck reads its cards in passes of its own: the case deck)
    !! and, for ncont_counted, the procedure that counts its continuation
    !! cards.
    type :: deck_card_t
        character(len=8) :: key = ''
        integer :: ncont = 0                    !! continuation cards (ncont_counted, ncont_optional: not fixed)
        integer :: times = any_times            !! any_times, at_most_once, exactly_once or once_per_file
        procedure(card_handler), pointer, nopass :: read    !! its handler (no default: a table names it, or null())
        procedure(card_counter), pointer, nopass :: count => null()   !! (ncont_counted) its continuation count
    end type deck_card_t

    !> A deck's format: its cards and what its messages name.
    type :: deck_format_t
        character(len=16) :: name = ''          !! the deck's kind in messages ("sweep cards have ...")
        character(len=32) :: doc = ''           !! where its cards are documented (an unknown card's message)
        logical :: title_first = .true.         !! a whole deck starts with its TITLE card
        type(deck_card_t), allocatable :: cards(:)
    end type deck_format_t

contains

    !> Whether the deck line after line i continues it (columns 1-10 blank).
    pure logical function continued(rd, i)
        type(deck_reader_t), intent(in) :: rd   !! the deck
        integer, intent(in) :: i                !! the card's deck line
        continued = i < rd%nlines
        if (continued) continued = len_trim(rd%lines(i + 1)%text(1:10)) == 0
    end function continued

    !> Read a deck's cards: split them (every shared check of
    !! group_deck_cards), then each card's handler in deck order, up to the
    !! first error; a required card missing is refused after the cards read
    !! (an error of a card comes first).
    subroutine read_deck_cards(deck, fmt)
        class(card_deck_t), intent(inout) :: deck   !! the deck being read; deck%rd%stat, errmsg: the first error
        type(deck_format_t), intent(in) :: fmt      !! its cards
        type(card_t), allocatable :: cards(:)
        integer :: k, e
        call split_cards(deck%rd, fmt, cards, fmt%title_first)
        do k = 1, size(cards)
            if (deck%rd%failed()) exit
            e = cards(k)%entry
            if (associated(fmt%cards(e)%read)) call fmt%cards(e)%read(deck, cards(k)%first)
        end do
        if (.not. deck%rd%failed()) call check_required(deck%rd, fmt, cards)
    end subroutine read_deck_cards

    !> Split the deck's lines into cards up to END, each checked against the
    !! table: its name, columns 9-10, TITLE first, its continuation cards,
    !! how many of it the deck holds (`times`), each required card there.
    !! `whole` false: a few card images of a deck (no TITLE first, no
    !! required card).
    subroutine group_deck_cards(rd, fmt, cards, whole)
        type(deck_reader_t), intent(inout) :: rd          !! the deck; a located error on the first bad card
        type(deck_format_t), intent(in) :: fmt            !! its cards
        type(card_t), allocatable, intent(out) :: cards(:) !! its cards in deck order, each with its entry
        logical, intent(in), optional :: whole            !! a whole deck (default: yes)
        logical :: all
        all = .true.
        if (present(whole)) all = whole
        call split_cards(rd, fmt, cards, all .and. fmt%title_first)
        if (all .and. .not. rd%failed()) call check_required(rd, fmt, cards)
    end subroutine group_deck_cards

    !> The cards of the deck's lines up to END, checked against the table
    !! (names, columns 9-10, TITLE first when `title`, continuation cards,
    !! how many of each).
    subroutine split_cards(rd, fmt, cards, title)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_format_t), intent(in) :: fmt
        type(card_t), allocatable, intent(out) :: cards(:)
        logical, intent(in) :: title
        integer :: i, nc, e, need
        allocate (cards(rd%nlines))
        nc = 0
        i = 1
        do while (i <= rd%nlines)
            if (rd%failed()) exit
            call card_entry(rd, fmt, i, e)
            if (e <= 0) exit                           ! END, or an error
            if (nc == 0 .and. title .and. rd%key(i) /= 'TITLE') then
                call rd%fail(rd%where(i)//', columns 1-8: found "'//trim(rd%key(i))//'"; expected a TITLE card first')
                exit
            end if
            call continuation_count(rd, fmt%cards(e), i, need)
            if (rd%failed()) exit
            nc = nc + 1
            cards(nc) = card_t(rd%key(i), i, need, e)
            i = i + need + 1
        end do
        cards = cards(1:nc)
        if (.not. rd%failed()) call check_times(rd, fmt, cards)
    end subroutine split_cards

    !> The table entry of the card at deck line i (0: END), or a located
    !! error (-1): a blank card name, text in columns 9-10, an unknown card.
    subroutine card_entry(rd, fmt, i, e)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_format_t), intent(in) :: fmt
        integer, intent(in) :: i
        integer, intent(out) :: e
        character(len=8) :: key
        e = -1
        if (len_trim(rd%lines(i)%text(1:10)) == 0) then
            if (any(fmt%cards%ncont /= 0)) then
                call rd%fail(rd%where(i)//', columns 1-8: found a continuation card (blank card name) '// &
                             'where a new card was expected; too many continuation cards for the card above?')
            else
                call rd%fail(rd%where(i)//', columns 1-8: found a blank card name; '//trim(fmt%name)// &
                             ' cards have no continuation cards')
            end if
            return
        end if
        if (rd%lines(i)%text(9:10) /= '  ') then
            call rd%fail(rd%where(i)//', columns 9-10: found "'//rd%lines(i)%text(9:10)// &
                         '"; expected blanks after the card name (fields start in column 11)')
            return
        end if
        key = rd%key(i)
        if (key == 'END') then
            e = 0
            return
        end if
        do e = 1, size(fmt%cards)           ! (a loop: no temporary of the key component)
            if (fmt%cards(e)%key == key) return
        end do
        e = -1
        call rd%fail(rd%where(i)//', columns 1-8: found unknown card "'//trim(key)//'"; expected one of '// &
                     card_list(fmt)//' ('//trim(fmt%doc)//')')
    end subroutine card_entry

    !> "TITLE, BASE, ... or END": the table's card names, cut short with
    !! "..." past max_list characters.
    function card_list(fmt) result(s)
        type(deck_format_t), intent(in) :: fmt
        character(len=:), allocatable :: s
        integer :: k
        s = ''
        do k = 1, size(fmt%cards)
            if (len(s) + len_trim(fmt%cards(k)%key) > max_list) then
                s = s//', ...'
                exit
            end if
            if (k > 1) s = s//', '
            s = s//trim(fmt%cards(k)%key)
        end do
        s = s//' or END'
    end function card_list

    !> The continuation cards of card `c` at deck line i, all there and
    !! blank in columns 1-10.
    subroutine continuation_count(rd, c, i, need)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_card_t), intent(in) :: c
        integer, intent(in) :: i
        integer, intent(out) :: need
        integer :: j
        select case (c%ncont)
        case (ncont_optional)
            need = merge(1, 0, continued(rd, i))
        case (ncont_counted)
            call c%count(rd, i, need)
            if (rd%failed()) return
        case default
            need = c%ncont
        end select
        if (i + need > rd%nlines) then
            call rd%fail(rd%where(i)//' ('//trim(c%key)//' card): the deck ends before its '// &
                         trim(int_str(need))//' continuation card(s)')
            return
        end if
        do j = i + 1, i + need
            if (len_trim(rd%lines(j)%text(1:10)) == 0) cycle
            call rd%fail(rd%where(j)//', columns 1-10: found "'//trim(rd%lines(j)%text(1:10))// &
                         '"; expected a continuation card of the '//trim(c%key)//' card above (columns 1-10 blank)')
            return
        end do
    end subroutine continuation_count

    !> Each card no more often than its entry's `times` allows (refused at
    !! the second, naming the first).
    subroutine check_times(rd, fmt, cards)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_format_t), intent(in) :: fmt
        type(card_t), intent(in) :: cards(:)
        integer :: seen(size(fmt%cards))     ! the first card of each entry (0: none yet)
        integer :: k, j, e
        seen = 0
        do k = 1, size(cards)
            e = cards(k)%entry
            select case (fmt%cards(e)%times)
            case (at_most_once, exactly_once)
                if (seen(e) > 0) then
                    call rd%fail(second(k)//'; expected only one (the first is at '//rd%where(cards(seen(e))%first)//')')
                    return
                end if
            case (once_per_file)
                do j = max(seen(e), 1), k - 1
                    if (cards(j)%entry /= e .or. rd%lines(cards(j)%first)%via /= rd%lines(cards(k)%first)%via) cycle
                    call rd%fail(second(k)//' in one file; expected only one in each file of the deck (the first is '// &
                                 'at '//rd%where(cards(j)%first)//'; an INCLUDEd file may hold one of its own)')
                    return
                end do
            end select
            if (seen(e) == 0) seen(e) = k
        end do
    contains
        !> "stdin line 9, columns 1-8 (DESIGN card): found a second DESIGN card".
        function second(k) result(s)
            integer, intent(in) :: k
            character(len=:), allocatable :: s
            s = rd%where(cards(k)%first)//', columns 1-8 ('//trim(cards(k)%key)//' card): found a second '// &
                trim(cards(k)%key)//' card'
        end function second
    end subroutine check_times

    !> Each card of exactly_once in the deck.
    subroutine check_required(rd, fmt, cards)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_format_t), intent(in) :: fmt
        type(card_t), intent(in) :: cards(:)
        integer :: e, k
        do e = 1, size(fmt%cards)
            if (fmt%cards(e)%times /= exactly_once) cycle
            do k = 1, size(cards)
                if (cards(k)%entry == e) exit
            end do
            if (k <= size(cards)) cycle
            call rd%fail(rd%top//': the deck has no '//trim(fmt%cards(e)%key)//' card; expected one '// &
                         trim(fmt%cards(e)%key)//' card')
            return
        end do
    end subroutine check_required

end module hn_card_engine
