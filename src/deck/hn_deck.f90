!> Interpretation of a fixed-format input deck into a run case. The cards
!! and their columns are documented in docs/deck-format.md; every error
!! names the source, line, columns, card and field, what was found and
!! what was expected. This module reads the deck, splits it into cards by
!! the card engine on the card registry (hn_cards) and runs the passes of
!! hn_deck_passes over them; each card group has its module
!! (hn_deck_control, _bodies, _scene, _coordinates, _tables, _elements,
!! _loads), on what they share (hn_deck_state). What the deck knows of the
!! element families (their cards, which repeats are refused, which fields
!! name a coordinate) is the family registry's (hn_families, `cards_with`),
!! also for families a program brings that the registry does not list
!! (`families`).
module hn_deck
    use hn_kinds, only: msglen
    use hn_case, only: case_t, deck_line_t
    use hn_deck_reader, only: deck_reader_t, read_card_images, int_str, upper
    use hn_model, only: model_set_neutral
    use hn_element_cards, only: family_card_t, unique_element, unique_name, unique_coordinate
    use hn_families, only: cards_with, family_registration_t
    use hn_integrators, only: integrator_names
    use hn_plausibility, only: plausibility_warnings
    use hn_changes, only: read_changes, apply_field_changes, kind_field
    use hn_sorting, only: sort_index_text
    use hn_deck_state, only: card_t, group_cards
    use hn_deck_passes, only: deck_reading_t, deck_pass_t, deck_passes
    implicit none
    private

    public :: read_case, read_case_lines, integrator_names

contains

    !> Read the deck in file `path` ('/dev/stdin' for standard input, named
    !! `source` in messages) into `cs`. INCLUDE files are looked for next to
    !! the including file, in the working directory, then in `include_path`.
    !! `change_cards` (the command line's --change options) are CHANGE card
    !! images put after the deck's own cards, located as "--change N".
    !! `families` are the entries of element families the registry does not
    !! list (a registry line each), put into the model after the registry's
    !! (model_add_family), whose cards the deck reads like the registry's.
    subroutine read_case(path, source, cs, stat, errmsg, include_path, change_cards, families)
        character(len=*), intent(in) :: path                       !! file to read
        character(len=*), intent(in) :: source                     !! its name in messages
        type(case_t), intent(out) :: cs                            !! the run case (model and run control)
        integer, intent(out) :: stat                               !! stat_ok, or stat_bad_input (the first error)
        character(len=msglen), intent(out) :: errmsg               !! the first error, located in the deck
        character(len=*), intent(in), optional :: include_path(:)  !! directories searched for INCLUDE files
        character(len=*), intent(in), optional :: change_cards(:)  !! CHANGE card images added after the deck's cards
        type(family_registration_t), intent(in), optional :: families(:)   !! entries of families outside the registry
        type(deck_reader_t) :: rd
        rd%top = source
        if (present(include_path)) rd%search = include_path
        call read_card_images(rd, path, source)
        if (.not. rd%failed() .and. rd%nlines == 0) &
            call rd%fail(source//' line 1: the deck is empty (no cards); expected a TITLE card first')
        if (present(change_cards) .and. .not. rd%failed()) call add_option_cards(rd, change_cards)
        if (present(families)) then
            call interpret(rd, cs, families)
        else
            call interpret(rd, cs, [family_registration_t ::])
        end if
        stat = rd%stat
        errmsg = rd%errmsg
    end subroutine read_case

    !> CHANGE card images from the command line (--change), checked as deck
    !! lines are (80 columns, plain ASCII) and put after the deck's own cards,
    !! before its END card; each is located as "--change N" in messages.
    subroutine add_option_cards(rd, images)
        type(deck_reader_t), intent(inout) :: rd
        character(len=*), intent(in) :: images(:)
        type(deck_line_t), allocatable :: extra(:)
        character(len=:), allocatable :: here
        integer :: k, j, c, n, iend
        allocate (extra(size(images)))
        do k = 1, size(images)
            here = '--change '//trim(int_str(k))
            n = len_trim(images(k))
            do j = 1, n
                c = iachar(images(k)(j:j))
                if (c >= 32 .and. c <= 126) cycle
                call rd%fail(here//', column '//trim(int_str(j))//': found a tab, control or non-ASCII '// &
                             'character; expected a card image of plain ASCII text')
                return
            end do
            if (n > 80) then
                call rd%fail(here//', columns 81-'//trim(int_str(n))//': found text beyond column 80; '// &
                             'card images have 80 columns')
                return
            end if
            if (upper(images(k)(1:min(n, 8))) /= 'CHANGE' .or. n < 11) then
                call rd%fail(here//', columns 1-8: found "'//trim(images(k)(1:min(n, 8)))//'"; expected a '// &
                             'CHANGE card image, e.g. --change ''CHANGE    HEADM     BODY      HEAD      MASS'// &
                             '      SCALE     1.1''')
                return
            end if
            extra(k)%text = images(k)(1:n)
            extra(k)%source = '--change'
            extra(k)%line = k
        end do
        iend = rd%nlines + 1
        do j = 1, rd%nlines
            if (rd%key(j) /= 'END') cycle
            iend = j
            exit
        end do
        rd%lines = [rd%lines(1:iend - 1), extra, rd%lines(iend:rd%nlines)]
        rd%nlines = rd%nlines + size(extra)
    end subroutine add_option_cards

    !> Interpret card images already read (INCLUDE expanded), as kept in
    !! `case_t%deck`: a deck edited in memory, e.g. one member of a sweep.
    !! `include_path` is searched for the data files of TABLE ... CSV cards
    !! as when the deck was read.
    subroutine read_case_lines(lines, source, cs, stat, errmsg, include_path)
        type(deck_line_t), intent(in) :: lines(:)      !! card images, INCLUDE cards expanded
        character(len=*), intent(in) :: source         !! name of the deck in messages
        type(case_t), intent(out) :: cs                !! the run case (model and run control)
        integer, intent(out) :: stat                   !! stat_ok, or stat_bad_input (the first error)
        character(len=msglen), intent(out) :: errmsg   !! the first error, located in the deck
        character(len=*), intent(in), optional :: include_path(:)  !! directories searched for data files
        type(deck_reader_t) :: rd
        rd%top = source
        if (present(include_path)) rd%search = include_path
        rd%lines = lines
        rd%nlines = size(lines)
        if (rd%nlines == 0) call rd%fail(source//': the deck is empty (no cards); expected a TITLE card first')
        call interpret(rd, cs, [family_registration_t ::])
        stat = rd%stat
        errmsg = rd%errmsg
    end subroutine read_case_lines

    !> The cards of `rd` into the case, card group by card group: the
    !! passes of hn_deck_passes (`deck_passes`) in their order; `families`
    !! (outside the registry) join the model after its bodies.
    subroutine interpret(rd, cs, families)
        type(deck_reader_t), intent(inout) :: rd
        type(case_t), intent(out) :: cs
        type(family_registration_t), intent(in) :: families(:)
        type(deck_reading_t) :: dr
        type(deck_pass_t), allocatable :: passes(:)
        type(family_card_t), allocatable :: fc(:)
        logical, allocatable :: coordinate(:)
        integer, allocatable :: first(:)
        integer :: k, p
        fc = cards_with(families)
        dr%st%fcards = fc
        dr%families = families
        coordinate = fc%coordinate   ! the family cards whose F1, F2 name a body and coordinate
        if (.not. rd%failed()) then
            cs%deck = rd%lines(1:rd%nlines)
            call group_cards(rd, dr%st%cards, more=fc)
        end if
        allocate (cs%scene(0), cs%changes(0), cs%subtitles(0))
        ! CHANGE cards: fields rewritten in rd's images (cs%deck keeps the deck as read)
        if (.not. rd%failed()) then
            allocate (first(0))
            do k = 1, size(dr%st%cards)
                if (dr%st%cards(k)%key == 'CHANGE') first = [first, dr%st%cards(k)%first]
            end do
            call read_changes(rd, first, dr%changes)
        end if
        ! cards that repeat one another are refused before a change can be ambiguous, and again
        ! when a change rewrote a field that identifies a card (F1, F2)
        if (.not. rd%failed()) call check_repeats(rd, dr%st%cards, fc)
        if (.not. rd%failed()) call apply_field_changes(rd, dr%changes, cs%changes, keys_of(fc, coordinate))
        if (.not. rd%failed()) then
            if (any(dr%changes%kind == kind_field .and. dr%changes%field <= 2)) call check_repeats(rd, dr%st%cards, fc)
        end if
        passes = deck_passes()
        do p = 1, size(passes)
            if (rd%failed()) exit
            call passes(p)%read(rd, dr, cs)
        end do
        if (.not. rd%failed()) call check_unknowns(rd, dr%st%cards, cs)
        if (.not. rd%failed()) then
            call model_set_neutral(cs%model)
            call plausibility_warnings(cs%model, cs%warnings)
            do k = 1, size(dr%st%tabs)
                if (len_trim(dr%st%tabs(k)%warning) > 0) &
                    cs%warnings = [character(len=160) :: cs%warnings, dr%st%tabs(k)%warning]
            end do
        end if
    end subroutine interpret

    !> A run needs at least one free coordinate: one that is neither locked
    !! nor prescribed (both builds refuse the same decks, before anything runs).
    subroutine check_unknowns(rd, cards, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(case_t), intent(in) :: cs
        integer :: k, last
        if (cs%model%tree%ndof - count(cs%model%prescribed) > 0) return
        last = 0
        do k = 1, size(cards)
            if (any(cards(k)%key == [character(len=8) :: 'LOCK', 'PRESCRIB', 'SCENE', 'MERGE'])) last = k
        end do
        if (last == 0) then
            call rd%fail(rd%top//': the model has no free coordinate; expected at least one coordinate '// &
                         'that is neither locked nor prescribed')
        else
            call rd%fail(rd%where(cards(last)%first)//' ('//trim(cards(last)%key)//' card): with this card '// &
                         'the model has no free coordinate left ('//trim(int_str(cs%model%tree%ndof))// &
                         ' active, all prescribed; '//trim(int_str(6*cs%model%tree%nbody - cs%model%tree%ndof))// &
                         ' locked); expected at least one coordinate that is neither locked nor prescribed')
        end if
    end subroutine check_unknowns

    !> Cards that must not say again what an earlier card said
    !! (docs/deck-format.md, "Cards that must not repeat"): a name used twice
    !! in one namespace, a second card for the same body and coordinate, an
    !! INITIAL card for a prescribed coordinate. Refused at the later card,
    !! with the earlier card's location. The families' cards say their own
    !! rule (`fc`, family_card_t's `unique`).
    subroutine check_repeats(rd, cards, fc)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(family_card_t), intent(in) :: fc(:)     !! the cards of the deck's element families
        character(len=*), parameter :: per_coordinate = 'one per body and coordinate'
        integer :: k
        call unique_fields(rd, cards, keys_of(fc, fc%unique == unique_element), 1, 'element name', &
                           'a name no other element card uses')
        call unique_fields(rd, cards, [character(len=8) :: 'TABLE', 'PULSE'], 1, 'table name', 'a new name')
        do k = 1, size(fc)
            if (fc(k)%unique == unique_name) call unique_fields(rd, cards, [fc(k)%key], 1, trim(fc(k)%what), 'a new name')
        end do
        call unique_fields(rd, cards, ['SCALE'], 1, 'factor name', 'a new name')
        call unique_fields(rd, cards, ['JOINT'], 1, 'body', 'one JOINT card per body')
        call unique_fields(rd, cards, ['BODYPI'], 1, 'body', 'one BODYPI card per body')
        call unique_fields(rd, cards, ['NEUTRAL'], 2, 'body and coordinate', per_coordinate)
        call unique_fields(rd, cards, ['INITIAL'], 2, 'body and coordinate', per_coordinate)
        call unique_fields(rd, cards, ['PRESCRIB'], 2, 'body and coordinate', per_coordinate)
        do k = 1, size(fc)
            if (fc(k)%unique == unique_coordinate) &
                call unique_fields(rd, cards, [fc(k)%key], 2, 'body and coordinate', per_coordinate)
        end do
        call unique_fields(rd, cards, [character(len=8) :: 'INITIAL', 'PRESCRIB'], 2, 'body and coordinate', &
                           'no INITIAL card for a prescribed coordinate (the PRESCRIB card gives its motion; '// &
                           'with ACCEL also its initial value and rate, F5 and F6)', across=.true.)
    end subroutine check_repeats

    !> The keys of the family cards fc that `pick` picks.
    pure function keys_of(fc, pick) result(keys)
        type(family_card_t), intent(in) :: fc(:)
        logical, intent(in) :: pick(:)              !! (size(fc)) which cards
        character(len=8), allocatable :: keys(:)
        integer :: k
        allocate (keys(0))
        do k = 1, size(fc)
            if (pick(k)) keys = [character(len=8) :: keys, fc(k)%key]
        end do
    end function keys_of

    !> Refuse a card of one of `keys` whose fields F1..F`nf` (upper case)
    !! equal those of an earlier card of `keys`; `across`: only pairs of
    !! cards of different keys (the same-key pairs have their own call).
    subroutine unique_fields(rd, cards, keys, nf, what, expected, across)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        character(len=*), intent(in) :: keys(:)      !! the card names that share the namespace
        integer, intent(in) :: nf                    !! fields F1..Fnf identify the card
        character(len=*), intent(in) :: what         !! what the fields hold (messages)
        character(len=*), intent(in) :: expected     !! what the rule expects (messages)
        logical, intent(in), optional :: across      !! only pairs of different keys (default: all pairs)
        integer, allocatable :: idx(:), ord(:)
        character(len=21), allocatable :: ident(:)
        integer :: k, n, j, f, r0, r1, m, q, kbad, jbad
        logical :: cross
        character(len=:), allocatable :: found, place
        if (rd%failed()) return
        idx = pack([(k, k=1, size(cards))], [(any(keys == cards(k)%key), k=1, size(cards))])
        n = size(idx)
        allocate (ident(n))
        do k = 1, n
            ident(k) = ''
            do f = 1, nf
                ident(k) = trim(ident(k))//' '//upper(rd%raw(cards(idx(k))%first, f))
            end do
        end do
        ! equal identifiers adjacent, each run in deck order (a stable sort: n log n
        ! for decks of many thousand cards); the first card that repeats an
        ! earlier one of its run, over all runs, is refused
        cross = .false.
        if (present(across)) cross = across
        ord = sort_index_text(ident)
        kbad = 0; jbad = 0
        r0 = 1
        do while (r0 <= n)
            r1 = r0
            do while (r1 < n)
                if (ident(ord(r1 + 1)) /= ident(ord(r0))) exit
                r1 = r1 + 1
            end do
            runs: do m = r0 + 1, r1
                k = ord(m)
                do q = r0, m - 1
                    j = ord(q)
                    if (cross .and. cards(idx(j))%key == cards(idx(k))%key) cycle
                    if (kbad == 0 .or. k < kbad) then
                        kbad = k; jbad = j
                    end if
                    exit runs
                end do
            end do runs
            r0 = r1 + 1
        end do
        if (kbad == 0) return
        k = kbad; j = jbad
        found = trim(adjustl(ident(k)))
        place = rd%where(cards(idx(k))%first)//', columns 11-'//trim(int_str(10 + 10*nf))//' ('// &
                trim(cards(idx(k))%key)//' card, '//what//')'
        if (cards(idx(j))%key == cards(idx(k))%key) then
            call rd%fail(place//': found "'//found//'" again; expected '// &
                         expected//' (the '//trim(cards(idx(j))%key)//' card at '// &
                         rd%where(cards(idx(j))%first)//' has it)')
        else
            call rd%fail(place//': found "'//found//'", which the '// &
                         trim(cards(idx(j))%key)//' card at '//rd%where(cards(idx(j))%first)// &
                         ' names too; expected '//expected)
        end if
    end subroutine unique_fields

end module hn_deck
