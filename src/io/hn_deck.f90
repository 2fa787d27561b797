!> Interpretation of a fixed-format input deck into a run case. The cards
!! and their columns are documented in docs/deck-format.md; every error
!! names the source, line, columns, card and field, what was found and
!! what was expected.
module hn_deck
    use hn_kinds, only: wp, zero, one, deg, msglen, g_std
    use hn_case, only: case_t, deck_line_t
    use hn_deck_reader, only: deck_reader_t, read_card_images, int_str, upper
    use hn_tree, only: body_tree_t, tree_allocate, tree_build, name_len
    use hn_model, only: model_init, model_set_neutral, neutral_coordinates, family_items, family_items_text, &
                        scale_family, max_family_items, model_set_family
    use hn_cards, only: card_known, card_ncont, card_repeats
    use hn_families, only: nfamilies, family_name, family_index, fam_discs, fam_ligaments, &
                           fam_muscles, fam_limits, fam_springs
    use hn_disc_family, only: disc_family_t
    use hn_ligament_family, only: ligament_family_t
    use hn_muscle_family, only: muscle_family_t
    use hn_limit_family, only: limit_family_t
    use hn_spring_family, only: spring_family_t
    use hn_motion, only: motion_constant, motion_accel_table, motion_position_table, motion_harmonic, motion_eval
    use hn_tables, only: table_t, table_set
    use hn_discs, only: disc_t
    use hn_line_elements, only: line_attach_t, ligament_t, muscle_t, spring_t, muscle_hill, max_via
    use hn_muscle, only: activation_t
    use hn_joint_limits, only: joint_limit_t, joint_range_t
    use hn_applied, only: applied_load_t, applied_force, applied_couple, frame_body, frame_inertial
    use hn_linsolve, only: solver_cholesky, solver_names, solver_code
    use hn_integrators, only: integrator_names
    use hn_rotation, only: norm3
    use hn_scene, only: merge_bodies, lock_sagittal
    use hn_plausibility, only: plausibility_warnings
    use hn_changes, only: change_t, read_changes, apply_field_changes, apply_model_changes, kind_field
    use hn_csv, only: read_two_columns
    use hn_sorting, only: sort_index_text
    use hn_criteria_card, only: criteria_card
    use hn_pulses, only: pulse_shapes, pulse_code, pulse_dv_factor, pulse_knots, pulse_triangle, pulse_trapezoid, &
                         pulse_halfsine
    implicit none
    private

    public :: read_case, read_case_lines, integrator_names

    character(len=2), parameter :: coord_names(6) = ['TX', 'TY', 'TZ', 'RX', 'RY', 'RZ']
    real(wp), parameter :: big_length = 10.0_wp     !! largest coordinate of a point [m]
    real(wp), parameter :: big_modulus = 1.0e13_wp  !! largest modulus or stiffness accepted
    integer, parameter :: max_table_points = 100000 !! points of one TABLE
    real(wp), parameter :: tiny_value = 1.0e-30_wp  !! a table whose values are all below this is zero in effect

    !> One card with its continuation cards: deck lines first .. first+ncont.
    type :: card_t
        character(len=8) :: key = ''
        integer :: first = 0
        integer :: ncont = 0
    end type card_t

    !> Where each body named in the deck went: its number in the reduced
    !! tree and the shift of points given in its frame (MERGE); the card line
    !! of the MERGE that absorbed it (0: not absorbed).
    type :: body_map_t
        integer, allocatable :: new(:)
        real(wp), allocatable :: shift(:, :)
        integer, allocatable :: merged_by(:)
        integer, allocatable :: locked_by(:, :)   !! (coordinate, deck body): the LOCK or SCENE card line that locked it (0: none)
    end type body_map_t

    !> A named table of the deck.
    type :: named_table_t
        character(len=10) :: name = ''
        type(table_t) :: tab
        integer :: line = 0
        character(len=160) :: warning = ''   !! a scale that makes the table zero in effect
    end type named_table_t

contains

    !> Read the deck in file `path` ('/dev/stdin' for standard input, named
    !! `source` in messages) into `cs`. INCLUDE files are looked for next to
    !! the including file, in the working directory, then in `include_path`.
    !! `change_cards` (the command line's --change options) are CHANGE card
    !! images put after the deck's own cards, located as "--change N".
    subroutine read_case(path, source, cs, stat, errmsg, include_path, change_cards)
        character(len=*), intent(in) :: path                       !! file to read
        character(len=*), intent(in) :: source                     !! its name in messages
        type(case_t), intent(out) :: cs                            !! the run case (model and run control)
        integer, intent(out) :: stat                               !! stat_ok, or stat_bad_input (the first error)
        character(len=msglen), intent(out) :: errmsg               !! the first error, located in the deck
        character(len=*), intent(in), optional :: include_path(:)  !! directories searched for INCLUDE files
        character(len=*), intent(in), optional :: change_cards(:)  !! CHANGE card images added after the deck's cards
        type(deck_reader_t) :: rd
        rd%top = source
        if (present(include_path)) rd%search = include_path
        call read_card_images(rd, path, source)
        if (.not. rd%failed() .and. rd%nlines == 0) &
            call rd%fail(source//' line 1: the deck is empty (no cards); expected a TITLE card first')
        if (present(change_cards) .and. .not. rd%failed()) call add_option_cards(rd, change_cards)
        call interpret(rd, cs)
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
        call interpret(rd, cs)
        stat = rd%stat
        errmsg = rd%errmsg
    end subroutine read_case_lines

    !> The cards of `rd` into the case, card group by card group.
    subroutine interpret(rd, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(case_t), intent(out) :: cs
        type(card_t), allocatable :: cards(:)
        type(named_table_t), allocatable :: tabs(:)
        character(len=10), allocatable :: bnames(:)
        type(body_map_t) :: bmap
        type(change_t), allocatable :: changes(:)
        integer, allocatable :: first(:)
        integer :: k
        if (.not. rd%failed()) then
            cs%deck = rd%lines(1:rd%nlines)
            call group_cards(rd, cards)
        end if
        allocate (cs%scene(0), cs%changes(0), cs%subtitles(0))
        ! CHANGE cards: fields rewritten in rd's images (cs%deck keeps the deck as read)
        if (.not. rd%failed()) then
            allocate (first(0))
            do k = 1, size(cards)
                if (cards(k)%key == 'CHANGE') first = [first, cards(k)%first]
            end do
            call read_changes(rd, first, changes)
        end if
        ! cards that repeat one another are refused before a change can be ambiguous, and again
        ! when a change rewrote a field that identifies a card (F1, F2)
        if (.not. rd%failed()) call check_repeats(rd, cards)
        if (.not. rd%failed()) call apply_field_changes(rd, changes, cs%changes)
        if (.not. rd%failed()) then
            if (any(changes%kind == kind_field .and. changes%field <= 2)) call check_repeats(rd, cards)
        end if
        if (.not. rd%failed()) call body_cards(rd, cards, cs, bnames, bmap)
        if (.not. rd%failed()) call control_cards(rd, cards, cs)
        if (.not. rd%failed()) call table_cards(rd, cards, tabs, cs)
        if (.not. rd%failed()) call coordinate_cards(rd, cards, cs, bnames, bmap, tabs)
        if (.not. rd%failed()) call element_cards(rd, cards, cs, bnames, bmap, tabs)
        if (.not. rd%failed()) call load_cards(rd, cards, cs, bnames, bmap, tabs)
        if (.not. rd%failed()) call report_cards(rd, cards, cs, bnames, bmap)
        if (.not. rd%failed()) call stiffen_cards(rd, cards, cs)
        if (.not. rd%failed()) call apply_model_changes(rd, changes, cs%model, cs%changes)
        if (.not. rd%failed()) call runlimit_card(rd, cards, cs)
        if (.not. rd%failed()) call check_unknowns(rd, cards, cs)
        if (.not. rd%failed()) then
            call model_set_neutral(cs%model)
            call plausibility_warnings(cs%model, cs%warnings)
            do k = 1, size(tabs)
                if (len_trim(tabs(k)%warning) > 0) cs%warnings = [character(len=160) :: cs%warnings, tabs(k)%warning]
            end do
        end if
    end subroutine interpret

    !> RUNLIMIT wall steps: stop the run (exit 3, files kept and marked
    !! incomplete) after this wall time [s] or this many steps; blank: no limit.
    subroutine runlimit_card(rd, cards, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(case_t), intent(inout) :: cs
        integer :: ic
        ic = single(rd, cards, 'RUNLIMIT', .false.)
        if (ic == 0 .or. rd%failed()) return
        call rd%real(cards(ic)%first, 1, 'wall-time limit', 's', cs%wall_limit, 1.0e-3_wp, 1.0e7_wp, default=zero)
        call rd%int(cards(ic)%first, 2, 'step limit', cs%step_limit, 1, huge(1), default=0)
        if (.not. rd%failed() .and. cs%wall_limit <= zero .and. cs%step_limit == 0) &
            call rd%fail(rd%where(cards(ic)%first)//', columns 11-30 (RUNLIMIT card): found no limit; '// &
                         'expected a wall time [s] in F1, a step count in F2, or both')
    end subroutine runlimit_card

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

    !> Split the lines into cards, checking names, continuation counts and
    !! that TITLE comes first.
    subroutine group_cards(rd, cards)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), allocatable, intent(out) :: cards(:)
        integer :: i, nc, need, npts, ios
        character(len=8) :: key
        character(len=10) :: s
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
            if (.not. card_known(key)) then
                call rd%fail(rd%where(i)//', columns 1-8: found unknown card "'//trim(key)// &
                             '"; expected one of TITLE CONTROL BODY JOINT ... (docs/deck-format.md)')
                return
            end if
            if (nc == 0 .and. key /= 'TITLE') then
                call rd%fail(rd%where(i)//', columns 1-8: found "'//trim(key)//'"; expected a TITLE card first')
                return
            end if
            need = card_ncont(key)
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
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        character(len=*), intent(in) :: key
        logical, intent(in) :: required
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

    !> Cards that must not say again what an earlier card said
    !! (docs/deck-format.md, "Cards that must not repeat"): a name used twice
    !! in one namespace, a second card for the same body and coordinate, an
    !! INITIAL card for a prescribed coordinate. Refused at the later card,
    !! with the earlier card's location.
    subroutine check_repeats(rd, cards)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        character(len=8), parameter :: elements(5) = [character(len=8) :: 'DISC', 'LIGAMENT', 'MUSCLE', 'HILL', &
                                                                            'SPRING']
        character(len=*), parameter :: per_coordinate = 'one per body and coordinate'
        call unique_fields(rd, cards, elements, 1, 'element name', 'a name no other element card uses')
        call unique_fields(rd, cards, [character(len=8) :: 'TABLE', 'PULSE'], 1, 'table name', 'a new name')
        call unique_fields(rd, cards, ['ACTIVATE'], 1, 'history name', 'a new name')
        call unique_fields(rd, cards, ['SCALE'], 1, 'factor name', 'a new name')
        call unique_fields(rd, cards, ['JOINT'], 1, 'body', 'one JOINT card per body')
        call unique_fields(rd, cards, ['BODYPI'], 1, 'body', 'one BODYPI card per body')
        call unique_fields(rd, cards, ['NEUTRAL'], 2, 'body and coordinate', per_coordinate)
        call unique_fields(rd, cards, ['INITIAL'], 2, 'body and coordinate', per_coordinate)
        call unique_fields(rd, cards, ['PRESCRIB'], 2, 'body and coordinate', per_coordinate)
        call unique_fields(rd, cards, ['LIMIT'], 2, 'body and coordinate', per_coordinate)
        call unique_fields(rd, cards, ['ROM'], 2, 'body and coordinate', per_coordinate)
        call unique_fields(rd, cards, [character(len=8) :: 'INITIAL', 'PRESCRIB'], 2, 'body and coordinate', &
                           'no INITIAL card for a prescribed coordinate (the PRESCRIB card gives its motion; '// &
                           'with ACCEL also its initial value and rate, F5 and F6)', across=.true.)
    end subroutine check_repeats

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

    !> TITLE: the deck's first card is its title. A deck that INCLUDEs a
    !! case deck (a variant of it) meets that deck's TITLE too: the first
    !! TITLE card of an INCLUDEd file is a subtitle, in deck order. A second
    !! TITLE card in one file is refused.
    subroutine title_cards(rd, cards, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(case_t), intent(inout) :: cs
        integer :: k, j, first, earlier, i
        first = 0
        do k = 1, size(cards)
            if (cards(k)%key /= 'TITLE') cycle
            i = cards(k)%first
            if (first == 0) then
                first = k
                cs%model%title = rd%text(i, 11)
                cycle
            end if
            earlier = 0
            if (rd%lines(i)%via == 0) earlier = first
            do j = first, k - 1
                if (earlier /= 0) exit
                if (cards(j)%key == 'TITLE' .and. rd%lines(cards(j)%first)%via == rd%lines(i)%via) earlier = j
            end do
            if (earlier /= 0) then
                call rd%fail(rd%where(i)//', columns 1-8: found a second TITLE card; expected only one (the '// &
                             'first is at '//rd%where(cards(earlier)%first)//'; the TITLE of an INCLUDEd deck '// &
                             'is a subtitle)')
                return
            end if
            cs%subtitles = [character(len=80) :: cs%subtitles, rd%text(i, 11)]
        end do
        if (first == 0) call rd%fail(rd%top//': the deck has no TITLE card; expected one')
    end subroutine title_cards

    !> TITLE, CONTROL, SOLVER, GRAVITY, OUTPUT, H5FILE, DUMP, HOLD.
    subroutine control_cards(rd, cards, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(case_t), intent(inout) :: cs
        integer :: ic, i, k, f, nd
        character(len=10) :: s
        real(wp) :: v, span
        real(wp), allocatable :: tmp(:)

        call title_cards(rd, cards, cs)
        if (rd%failed()) return

        ic = single(rd, cards, 'CONTROL', .true.)
        if (rd%failed()) return
        i = cards(ic)%first
        call rd%real(i, 7, 'start time', 's', cs%t_start, -1.0e4_wp, 1.0e4_wp, default=zero)
        call rd%real(i, 1, 'end time', 's', cs%t_end, -1.0e4_wp, 1.0e4_wp)
        if (.not. rd%failed() .and. .not. (cs%t_end > cs%t_start)) then
            call rd%fail(rd%context(i, 1, 'end time')//': found '// &
                         trim(rd%raw(i, 1))//' s; expected an end time after the start time '// &
                         trim(real_str(cs%t_start))//' s')
            return
        end if
        span = cs%t_end - cs%t_start
        call rd%real(i, 2, 'step', 's', cs%h, 1.0e-12_wp, 1.0e4_wp)
        if (rd%failed()) return
        cs%control_at = rd%context(i, 2, 'step')
        if (span/cs%h > 1.0e8_wp) then
            call rd%fail(rd%context(i, 2, 'step')//': found '// &
                         trim(rd%raw(i, 2))//' s; a step this small needs more than 1E8 steps for the run; '// &
                         'expected a step of at least '//trim(real_str(span*1.0e-8_wp))//' s')
            return
        end if
        if (cs%h > span) then
            call rd%fail(rd%context(i, 2, 'step')//': found '// &
                         trim(rd%raw(i, 2))//' s; expected a step no longer than the run ('// &
                         trim(real_str(span))//' s)')
            return
        end if
        call rd%real(i, 3, 'print interval', 's', cs%print_dt, 1.0e-9_wp, 1.0e4_wp)
        if (rd%failed()) return
        if (span/cs%print_dt > 1.0e6_wp) then
            call rd%fail(rd%context(i, 3, 'print interval')//': found '// &
                         trim(rd%raw(i, 3))//' s; expected at most 1E6 print times in the run')
            return
        end if
        call rd%name(i, 4, 'integrator', s)
        if (.not. rd%failed()) then
            if (.not. any(integrator_names == s(1:8))) then
                call rd%fail(rd%context(i, 4, 'integrator')//': found "'// &
                             trim(s)//'"; expected one of '//join(integrator_names))
                return
            end if
            cs%integrator = s(1:8)
        end if
        call rd%real(i, 5, 'relative tolerance', '-', cs%rtol, 1.0e-14_wp, 0.1_wp, default=1.0e-6_wp)
        call rd%real(i, 6, 'absolute tolerance', '-', cs%atol, 1.0e-16_wp, 1.0_wp, default=1.0e-8_wp)
        if (rd%failed()) return

        ! SOLVER: how a_ij xddot = f is solved (default CHOLESKY: a_ij and f_i by
        ! the recursive forms) and the Jacobian of the stiff integrators
        ! (default STRUCT: from the elements' tangent; FD: differences)
        cs%model%solver = solver_cholesky
        ic = single(rd, cards, 'SOLVER', .false.)
        if (ic > 0) then
            i = cards(ic)%first
            call rd%name(i, 1, 'method', s)
            if (rd%failed()) return
            cs%model%solver = solver_code(trim(s))
            if (cs%model%solver == 0) then
                call rd%fail(rd%context(i, 1, 'method')//': found "'//trim(s)//'"; expected one of '// &
                             join(solver_names))
                return
            end if
            if (len_trim(rd%raw(i, 2)) > 0) then
                call rd%choice(i, 2, 'Jacobian', [character(len=6) :: 'STRUCT', 'FD'], s)
                if (rd%failed()) return
                cs%model%jacobian = s(1:8)
            end if
        end if
        ic = single(rd, cards, 'GRAVITY', .false.)
        if (ic > 0) then
            do f = 1, 3
                call rd%real(cards(ic)%first, f, 'gravity component', 'm/s^2', v, -1.0e3_wp, 1.0e3_wp)
                cs%model%gravity(f) = v
            end do
        end if
        cs%sample_dt = min(cs%print_dt, 1.0e-4_wp)
        ic = single(rd, cards, 'OUTPUT', .false.)
        if (ic > 0) then
            call rd%real(cards(ic)%first, 1, 'HDF5 sample interval', 's', cs%sample_dt, 1.0e-9_wp, 1.0e4_wp)
            if (rd%failed()) return
            if (span/cs%sample_dt > 1.0e7_wp) &
                call rd%fail(rd%context(cards(ic)%first, 1, 'HDF5 sample interval')// &
                             ': expected at most 1E7 samples in the run')
            if (len_trim(rd%raw(cards(ic)%first, 2)) > 0) then
                call rd%choice(cards(ic)%first, 2, 'output accelerations', [character(len=7) :: 'HERMITE', 'SOLVE'], s)
                if (rd%failed()) return
                cs%output_xdd = s(1:8)
            end if
        end if
        ic = single(rd, cards, 'H5FILE', .false.)
        if (ic > 0) cs%h5file = rd%text(cards(ic)%first, 11)
        ic = single(rd, cards, 'EVENTS', .false.)
        if (ic > 0) then
            call rd%choice(cards(ic)%first, 1, 'event handling', [character(len=5) :: 'NONE', 'TIME', 'STATE'], s)
            cs%events = s(1:8)
        end if
        ic = single(rd, cards, 'HOLD', .false.)
        if (ic > 0) then
            call rd%name(cards(ic)%first, 1, 'option', s)
            if (s /= 'POSTURE' .and. .not. rd%failed()) &
                call rd%fail(rd%context(cards(ic)%first, 1, 'option')//': found "'//trim(s)//'"; expected POSTURE')
            cs%hold_posture = .true.
        end if
        allocate (cs%dump_times(0))
        do k = 1, size(cards)
            if (cards(k)%key /= 'DUMP') cycle
            i = cards(k)%first
            nd = 0
            do f = 1, 7
                if (rd%is_blank(i, f)) cycle
                call rd%real(i, f, 'dump time', 's', v, cs%t_start, cs%t_end)
                tmp = [cs%dump_times, v]
                call move_alloc(tmp, cs%dump_times)
                nd = nd + 1
            end do
            if (nd == 0 .and. .not. rd%failed()) &
                call rd%fail(rd%where(i)//', columns 11-80 (DUMP card): found no times; expected 1 to 7 times [s]')
        end do
    end subroutine control_cards

    !> BODY, BODYPI, JOINT, LOCK, NEUTRAL, SCENE, MERGE: the tree tables.
    subroutine body_cards(rd, cards, cs, bnames, bmap)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(case_t), intent(inout) :: cs
        character(len=10), allocatable, intent(out) :: bnames(:)
        type(body_map_t), intent(out) :: bmap
        character(len=10), allocatable :: pnames(:)
        integer, allocatable :: bline(:)
        integer :: nb, k, kb, i, f, p, m, stat, bad
        character(len=msglen) :: msg
        real(wp) :: v
        type(body_tree_t) :: tree

        nb = count(cards%key == 'BODY')
        if (nb == 0) then
            call rd%fail(rd%top//': the deck has no BODY card; expected at least one body')
            return
        end if
        allocate (bnames(nb), pnames(nb), bline(nb), bmap%locked_by(6, nb))
        bmap%locked_by = 0
        call tree_allocate(cs%model%tree, nb)
        kb = 0
        do k = 1, size(cards)
            if (cards(k)%key /= 'BODY') cycle
            kb = kb + 1
            i = cards(k)%first
            bline(kb) = i
            call body_name(rd, i, bnames(1:kb - 1), bnames(kb))
            if (rd%failed()) return
            call rd%name(i, 2, 'parent body', pnames(kb))
            call rd%real(i, 3, 'mass', 'kg', cs%model%tree%mass(kb), 1.0e-6_wp, 1.0e4_wp)
            cs%model%tree%inertia(:, :, kb) = zero
            do f = 1, 3
                call rd%real(i, 3 + f, 'principal inertia', 'kg m^2', v, 1.0e-12_wp, 1.0e4_wp)
                cs%model%tree%inertia(f, f, kb) = v
            end do
            cs%model%tree%name(kb) = bnames(kb)
        end do
        if (rd%failed()) return
        do kb = 1, nb
            if (pnames(kb) == 'R' .or. pnames(kb) == 'INERTIAL') then
                cs%model%tree%parent(kb) = 0
            else
                p = findloc(bnames, pnames(kb), dim=1)
                if (p == 0) then
                    call rd%fail(rd%context(bline(kb), 2, 'parent body')//': found "'//trim(pnames(kb))// &
                                 '"; expected R (inertial frame) or a body defined on a BODY card')
                    return
                end if
                cs%model%tree%parent(kb) = p
            end if
        end do
        call check_roots(rd, cs%model%tree%parent, bnames, bline)
        if (rd%failed()) return

        do k = 1, size(cards)
            i = cards(k)%first
            select case (cards(k)%key)
            case ('BODYPI')
                kb = body_ref(rd, i, 1, 'body', bnames, .false.)
                if (rd%failed()) return
                call rd%real(i, 2, 'product of inertia Ixy', 'kg m^2', v, -1.0e4_wp, 1.0e4_wp)
                cs%model%tree%inertia(1, 2, kb) = v; cs%model%tree%inertia(2, 1, kb) = v
                call rd%real(i, 3, 'product of inertia Ixz', 'kg m^2', v, -1.0e4_wp, 1.0e4_wp)
                cs%model%tree%inertia(1, 3, kb) = v; cs%model%tree%inertia(3, 1, kb) = v
                call rd%real(i, 4, 'product of inertia Iyz', 'kg m^2', v, -1.0e4_wp, 1.0e4_wp)
                cs%model%tree%inertia(2, 3, kb) = v; cs%model%tree%inertia(3, 2, kb) = v
            case ('JOINT')
                kb = body_ref(rd, i, 1, 'body', bnames, .false.)
                if (rd%failed()) return
                do f = 1, 3
                    call rd%real(i, 1 + f, 'joint point in parent', 'm', v, -big_length, big_length)
                    cs%model%tree%joint_parent(f, kb) = v
                    call rd%real(i, 4 + f, 'joint point in body', 'm', v, -big_length, big_length)
                    cs%model%tree%joint_child(f, kb) = v
                end do
            case ('LOCK')
                call lock_card(rd, i, bnames, cs, bmap%locked_by)
            case ('NEUTRAL')
                kb = body_ref(rd, i, 1, 'body', bnames, .false.)
                m = coord_ref(rd, i, 2)
                if (rd%failed()) return
                call rd%real(i, 3, 'neutral value', unit_of(m), v, -unit_limit(m), unit_limit(m))
                cs%model%tree%q_ref(m, kb) = v*unit_factor(m)
            end select
            if (rd%failed()) return
        end do

        call tree_build(cs%model%tree, stat, msg, bad)
        if (stat /= 0) then
            call rd%fail(body_place(bad)//': '//trim(msg))
            return
        end if
        allocate (bmap%new(nb), bmap%shift(3, nb), bmap%merged_by(nb))
        bmap%new = [(k, k=1, nb)]
        bmap%shift = zero
        bmap%merged_by = 0
        call scene_cards(rd, cards, cs, bnames, bmap)
        if (rd%failed()) return
        call tree_build(cs%model%tree, stat, msg)
        if (stat /= 0) then
            call rd%fail(rd%where(cards(findloc(cards%key, 'MERGE', dim=1, back=.true.))%first)// &
                         ' (MERGE cards): '//trim(msg))
            return
        end if
        tree = cs%model%tree       ! model_init takes the tree by value (its model argument is intent(out))
        call model_init(cs%model, tree)
    contains
        !> The BODY card of body kb (and its BODYPI card, if any) in messages.
        function body_place(kbad) result(s)
            integer, intent(in) :: kbad
            character(len=:), allocatable :: s
            integer :: kk
            if (kbad < 1 .or. kbad > nb) then
                s = rd%top//' (BODY cards)'
                return
            end if
            s = rd%where(bline(kbad))//' (BODY card '//trim(bnames(kbad))
            do kk = 1, size(cards)
                if (cards(kk)%key /= 'BODYPI') cycle
                if (upper(rd%raw(cards(kk)%first, 1)) == bnames(kbad)) &
                    s = s//'; its BODYPI card is at '//rd%where(cards(kk)%first)
            end do
            s = s//')'
        end function body_place
    end subroutine body_cards

    !> The name of a new body on BODY card image i: not a name of the
    !! inertial frame, not reserved, not too long, not a name already used.
    subroutine body_name(rd, i, earlier, name)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i                      !! the BODY card image
        character(len=10), intent(in) :: earlier(:)   !! the bodies defined before it
        character(len=10), intent(out) :: name        !! its name
        call rd%name(i, 1, 'body name', name)
        if (rd%failed()) return
        if (name == 'R' .or. name == 'INERTIAL') then
            call rd%fail(rd%context(i, 1, 'body name')//': found "'//trim(name)//'", which names the '// &
                         'inertial frame (R, alias INERTIAL); expected another name')
        else if (name == 'ALL') then
            call rd%fail(rd%context(i, 1, 'body name')//': found "ALL", a reserved word (LOCK ALL '// &
                         'means every body); expected another name')
        else if (len_trim(name) > name_len) then
            call rd%fail(rd%context(i, 1, 'body name')//': found "'//trim(name)//'"; expected at most 12 characters')
        else if (any(earlier == name)) then
            call rd%fail(rd%context(i, 1, 'body name')//': body "'//trim(name)// &
                         '" is defined twice; expected a new name')
        end if
    end subroutine body_name

    !> Exactly one body hangs from R, and following parents from any body
    !! reaches it: errors name the BODY cards concerned.
    subroutine check_roots(rd, parent, bnames, bline)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: parent(:), bline(:)
        character(len=10), intent(in) :: bnames(:)
        integer :: nroot, k, p, steps, r1
        character(len=:), allocatable :: loop
        nroot = count(parent == 0)
        if (nroot > 1) then
            r1 = findloc(parent, 0, dim=1)
            k = findloc(parent(r1 + 1:), 0, dim=1) + r1
            call rd%fail(rd%context(bline(k), 2, 'parent body')//': body '//trim(bnames(k))// &
                         ' has parent R, and so has body '//trim(bnames(r1))//' ('//rd%where(bline(r1))//'); '// &
                         trim(int_str(nroot))//' bodies have parent R; expected exactly one root body '// &
                         '(the tree hangs from one body)')
            return
        end if
        ! a body whose chain of parents does not reach R within nb steps lies on or hangs from a loop
        do k = 1, size(parent)
            p = k
            steps = 0
            do while (p /= 0 .and. steps <= size(parent))
                p = parent(p)
                steps = steps + 1
            end do
            if (p == 0) cycle
            ! walk on until a body repeats: that body is on the loop
            p = k
            do steps = 1, size(parent)
                p = parent(p)
            end do
            loop = trim(bnames(p))
            r1 = parent(p)
            do while (r1 /= p)
                loop = loop//' -> '//trim(bnames(r1))
                r1 = parent(r1)
            end do
            loop = loop//' -> '//trim(bnames(p))
            if (nroot == 0) then
                call rd%fail(rd%context(bline(p), 2, 'parent body')//': 0 bodies have parent R; body '// &
                             trim(bnames(p))//' lies on a loop of parents ('//loop//'); expected an open tree '// &
                             'hanging from one body with parent R')
            else
                call rd%fail(rd%context(bline(p), 2, 'parent body')//': body '//trim(bnames(p))// &
                             ' lies on a loop of parents ('//loop//'); expected an open tree hanging from one '// &
                             'body with parent R')
            end if
            return
        end do
        if (nroot == 0) call rd%fail(rd%top//': no BODY card has parent R; expected exactly one root body')
    end subroutine check_roots

    !> SCENE SAGITTAL and MERGE survivor absorbed...: reduce the model to what
    !! the scene needs; notes for the listing.
    subroutine scene_cards(rd, cards, cs, bnames, bmap)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(case_t), intent(inout) :: cs
        character(len=10), intent(in) :: bnames(:)
        type(body_map_t), intent(inout) :: bmap
        integer :: ic, k, i, f, nabs, surv, kk, stat
        integer, allocatable :: absorbed(:), new_index(:)
        real(wp), allocatable :: shift(:, :)
        character(len=10) :: s
        character(len=msglen) :: msg
        character(len=100) :: note
        ic = single(rd, cards, 'SCENE', .false.)
        if (ic > 0) then
            call rd%choice(cards(ic)%first, 1, 'scene', [character(len=8) :: 'SAGITTAL', 'FULL'], s)
            if (rd%failed()) return
            if (s == 'SAGITTAL') then
                call lock_sagittal(cs%model%tree)
                do f = 2, 6, 2
                    where (bmap%locked_by(f, :) == 0) bmap%locked_by(f, :) = cards(ic)%first
                end do
                call add_note('SCENE SAGITTAL: TY, RX, RZ OF EVERY BODY LOCKED AT NEUTRAL')
            end if
        end if
        do k = 1, size(cards)
            if (cards(k)%key /= 'MERGE') cycle
            i = cards(k)%first
            surv = body_ref(rd, i, 1, 'surviving body', bnames, .false.)
            allocate (absorbed(0))
            do f = 2, 7
                if (rd%is_blank(i, f)) cycle
                kk = body_ref(rd, i, f, 'absorbed body', bnames, .false.)
                if (rd%failed()) return
                absorbed = [absorbed, kk]
            end do
            if (rd%failed()) return
            if (size(absorbed) == 0) then
                call rd%fail(rd%where(i)//', columns 21-80 (MERGE card): found no body to absorb; expected 1 to 6')
                return
            end if
            ! bodies already merged are addressed through their survivor
            surv = bmap%new(surv)
            absorbed = bmap%new(absorbed)
            if (any(absorbed == surv)) then
                call rd%fail(rd%where(i)//' (MERGE card): a body cannot absorb itself (or one already merged into it)')
                return
            end if
            allocate (new_index(cs%model%tree%nbody), shift(3, cs%model%tree%nbody))
            call merge_bodies(cs%model%tree, surv, absorbed, new_index, shift, stat, msg)
            if (stat /= 0) then
                call rd%fail(rd%where(i)//' (MERGE card): '//trim(msg))
                return
            end if
            ! compose with the map so far
            do kk = 1, size(bmap%new)
                bmap%shift(:, kk) = bmap%shift(:, kk) + shift(:, bmap%new(kk))
                if (any(absorbed == bmap%new(kk))) bmap%merged_by(kk) = i
                bmap%new(kk) = new_index(bmap%new(kk))
            end do
            nabs = size(absorbed)
            write (note, '(a,i0,3a)') 'MERGE: ', nabs, ' BODIES ABSORBED INTO ', &
                trim(cs%model%tree%name(new_index(surv))), ' (MASS, INERTIA BY THE PARALLEL-AXIS THEOREM)'
            call add_note(note)
            deallocate (absorbed, new_index, shift)
        end do
    contains
        subroutine add_note(text)
            character(len=*), intent(in) :: text
            call add_scene_note(cs, text)
        end subroutine add_note
    end subroutine scene_cards

    !> LOCK body|ALL coordinate ...: lock coordinates at their neutral value.
    subroutine lock_card(rd, i, bnames, cs, locked_by)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i
        character(len=10), intent(in) :: bnames(:)
        type(case_t), intent(inout) :: cs
        integer, intent(inout) :: locked_by(:, :)    !! (coordinate, body): the card that locked it first
        character(len=10) :: s
        integer :: kb, f, m, nset
        call rd%name(i, 1, 'body', s)
        if (rd%failed()) return
        kb = 0
        if (s /= 'ALL') kb = body_ref(rd, i, 1, 'body', bnames, .false.)
        nset = 0
        do f = 2, 7
            if (rd%is_blank(i, f)) cycle
            m = coord_ref(rd, i, f)
            if (rd%failed()) return
            if (kb == 0) then
                cs%model%tree%active(m, :) = .false.
                where (locked_by(m, :) == 0) locked_by(m, :) = i
            else
                cs%model%tree%active(m, kb) = .false.
                if (locked_by(m, kb) == 0) locked_by(m, kb) = i
            end if
            nset = nset + 1
        end do
        if (nset == 0) call rd%fail(rd%where(i)//', columns 21-80 (LOCK card): found no coordinate; '// &
                                    'expected one to six of TX TY TZ RX RY RZ')
    end subroutine lock_card

    !> TABLE cards with their data continuation cards, and PULSE cards
    !! (tables of the same namespace, in deck order).
    subroutine table_cards(rd, cards, tabs, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(named_table_t), allocatable, intent(out) :: tabs(:)
        type(case_t), intent(inout) :: cs
        integer :: k, nt, i, npts, c, stat, bad
        character(len=12) :: v1, v2
        real(wp) :: tscale, yscale
        real(wp), allocatable :: t(:), y(:)
        nt = count(cards%key == 'TABLE' .or. cards%key == 'PULSE')
        allocate (tabs(nt))
        nt = 0
        do k = 1, size(cards)
            if (cards(k)%key == 'PULSE') then
                nt = nt + 1
                call pulse_card(rd, cards(k)%first, tabs(nt), cs)
                if (rd%failed()) return
                cycle
            end if
            if (cards(k)%key /= 'TABLE') cycle
            nt = nt + 1
            i = cards(k)%first
            tabs(nt)%line = i
            call rd%name(i, 1, 'table name', tabs(nt)%name)
            if (rd%failed()) return
            call rd%int(i, 2, 'number of points', npts, 1, max_table_points)
            call rd%real(i, 3, 'time scale', 's per unit', tscale, 1.0e-9_wp, 1.0e3_wp, default=one)
            call rd%real(i, 4, 'value scale', 'per unit', yscale, -1.0e9_wp, 1.0e9_wp, default=one)
            if (rd%failed()) return
            if (upper(adjustl(rd%raw(i, 5))) == 'CSV') then
                call csv_points(rd, i, tabs(nt)%name, npts, t, y)
            else
                call card_points(rd, i, cards(k)%ncont, tabs(nt)%name, npts, t, y)
            end if
            if (rd%failed()) return
            if (maxval(abs(y)) > zero .and. maxval(abs(y))*abs(yscale) < tiny_value) then
                write (v1, '(es11.2e3)') yscale
                write (v2, '(es11.2e3)') maxval(abs(y))*abs(yscale)
                tabs(nt)%warning = 'table '//trim(tabs(nt)%name)//': value scale '//trim(adjustl(v1))// &
                                   ' makes its largest value '//trim(adjustl(v2))//', zero in effect; check F4 at '// &
                                   rd%where(i)
            end if
            call table_set(tabs(nt)%tab, t*tscale, y*yscale, stat, bad)
            if (bad > 0) then
                c = i + 1 + (bad - 1)/3
                call rd%fail(rd%where(c)//' (TABLE '//trim(tabs(nt)%name)//' data, point '// &
                             trim(int_str(bad))//'): times must increase strictly; found '// &
                             trim(real_str(t(bad)))//' after '//trim(real_str(t(bad - 1))))
                return
            end if
            deallocate (t, y)
        end do
    end subroutine table_cards

    !> PULSE name shape peak dv duration onset f: a table of a named
    !! shape (hn_pulses), given its peak or its velocity change.
    subroutine pulse_card(rd, i, tab, cs)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i                   !! the PULSE card image
        type(named_table_t), intent(inout) :: tab  !! the table (name, knots, line)
        type(case_t), intent(inout) :: cs          !! the case (the listing's note of the pulse)
        character(len=10) :: s
        character(len=:), allocatable :: note, shape_text
        character(len=12) :: v
        real(wp) :: peak, dv, duration, onset, frac, factor
        real(wp), allocatable :: t(:), a(:)
        integer :: code, stat
        tab%line = i
        call rd%name(i, 1, 'table name', tab%name)
        call rd%choice(i, 2, 'shape', pulse_shapes, s)
        if (rd%failed()) return
        code = pulse_code(s)
        if (rd%is_blank(i, 3) .eqv. rd%is_blank(i, 4)) then
            call rd%fail(rd%where(i)//', columns 31-50 (PULSE card, peak and velocity change): found '// &
                         trim(merge('both   ', 'neither', .not. rd%is_blank(i, 3)))//'; expected either the peak (F3) '// &
                         'or the velocity change (F4), the other blank')
            return
        end if
        call rd%real(i, 5, 'duration', 's', duration, 1.0e-6_wp, 1.0e3_wp)
        call rd%real(i, 6, 'onset', 's', onset, zero, 1.0e3_wp, default=zero)
        frac = 0.5_wp
        select case (code)
        case (pulse_triangle)
            call rd%real(i, 7, 'time of the peak', 'fraction of the duration', frac, 0.001_wp, 0.999_wp, &
                         default=0.5_wp)
        case (pulse_trapezoid)
            call rd%real(i, 7, 'rise time', 'fraction of the duration', frac, 0.001_wp, 0.499_wp, default=0.25_wp)
        case default
            if (.not. rd%is_blank(i, 7)) then
                call rd%fail(rd%context(i, 7, 'fraction')//': found "'//trim(rd%raw(i, 7))//'"; expected blank '// &
                             '(F7 is the time of the peak of a TRIANGLE or the rise time of a TRAPEZOID)')
                return
            end if
        end select
        if (rd%failed()) return
        factor = pulse_dv_factor(code, duration, frac)
        if (.not. rd%is_blank(i, 3)) then
            call rd%real(i, 3, 'peak', 'table unit', peak, -1.0e9_wp, 1.0e9_wp)
            if (rd%failed()) return
            if (peak == zero) call rd%fail(rd%context(i, 3, 'peak')//': found 0; expected a non-zero peak')
            dv = peak*factor
        else
            call rd%real(i, 4, 'velocity change', 'table unit x s', dv, -1.0e9_wp, 1.0e9_wp)
            if (rd%failed()) return
            if (dv == zero) call rd%fail(rd%context(i, 4, 'velocity change')// &
                                         ': found 0; expected a non-zero velocity change')
            peak = dv/factor
        end if
        if (rd%failed()) return
        call pulse_knots(code, peak, duration, onset, frac, t, a)
        call table_set(tab%tab, t, a, stat)
        if (stat /= 0) then
            call rd%fail(rd%where(i)//' (PULSE '//trim(tab%name)//'): the pulse makes no table')
            return
        end if
        select case (code)
        case (pulse_halfsine); shape_text = 'HALF-SINE'
        case (pulse_triangle); write (v, '(f0.2)') frac; shape_text = 'TRIANGLE (PEAK AT '//trim(zero_lead(v))//' T)'
        case (pulse_trapezoid); write (v, '(f0.2)') frac; shape_text = 'TRAPEZOID (RISE '//trim(zero_lead(v))//' T)'
        case default; shape_text = trim(pulse_shapes(code))
        end select
        write (v, '(f0.2)') peak/g_std
        note = 'PULSE '//trim(tab%name)//': '//shape_text//', PEAK '//three_digits(peak)//' ('// &
               '9.80665 M/S2 = 1 G: '//trim(zero_lead(v))//' G), DV '//three_digits(dv)//', '// &
               ms(duration)//' MS FROM '//ms(onset)//' MS'
        if (len(note) > 100) note = 'PULSE '//trim(tab%name)//': '//shape_text//', PEAK '//three_digits(peak)// &
                                    ' ('//trim(zero_lead(v))//' G), DV '//three_digits(dv)//', '// &
                                    ms(duration)//' MS FROM '//ms(onset)//' MS'
        call add_scene_note(cs, note)
    contains
        !> x with three significant digits (E format outside 0.01 .. 1E5).
        function three_digits(x) result(r)
            real(wp), intent(in) :: x
            character(len=:), allocatable :: r
            character(len=16) :: b
            integer :: e
            if (abs(x) >= 0.01_wp .and. abs(x) < 1.0e5_wp) then
                e = floor(log10(abs(x)))
                write (b, '(f0.'//achar(48 + max(0, 2 - e))//')') x
                b = zero_lead(b)
                if (max(0, 2 - e) == 0) b = trim(b)//'.0'
            else
                write (b, '(es10.2)') x
            end if
            r = trim(adjustl(b))
        end function three_digits
        !> A time [s] in ms with one decimal.
        function ms(x) result(r)
            real(wp), intent(in) :: x
            character(len=:), allocatable :: r
            character(len=16) :: b
            write (b, '(f0.1)') 1000*x
            r = trim(zero_lead(b))
        end function ms
    end subroutine pulse_card

    !> A number written with f0.d, with its leading zero (".5" -> "0.5").
    pure function zero_lead(b) result(r)
        character(len=*), intent(in) :: b
        character(len=len(b) + 1) :: r
        character(len=len(b)) :: c
        c = adjustl(b)
        if (c(1:1) == '.') then
            r = '0'//c
        else if (c(1:2) == '-.') then
            r = '-0'//c(2:)
        else
            r = c
        end if
    end function zero_lead

    !> The npts (time, value) points of a TABLE on its continuation cards:
    !! three pairs per card, fields after the last point blank.
    subroutine card_points(rd, i, ncont, name, npts, t, y)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, ncont, npts       !! TABLE card image, its continuation cards, points
        character(len=*), intent(in) :: name        !! table name (messages)
        real(wp), allocatable, intent(out) :: t(:), y(:)
        integer :: j, c, f
        allocate (t(npts), y(npts))
        do j = 1, npts
            c = i + 1 + (j - 1)/3
            f = 2*mod(j - 1, 3) + 1
            call rd%real(c, f, 'time', 'table time unit', t(j), -1.0e7_wp, 1.0e7_wp)
            call rd%real(c, f + 1, 'value', 'table unit', y(j), -1.0e12_wp, 1.0e12_wp)
        end do
        if (rd%failed()) return
        c = i + ncont
        do f = 2*mod(npts - 1, 3) + 3, 7
            if (.not. rd%is_blank(c, f)) then
                call rd%fail(rd%where(c)//' (TABLE '//trim(name)//' data): found "'// &
                             trim(rd%raw(c, f))//'" in field F'//achar(48 + f)//' after the last of '// &
                             trim(int_str(npts))//' points; expected blank (or a larger point count)')
                return
            end if
        end do
    end subroutine card_points

    !> The npts points of a TABLE from the two-column file named on its
    !! continuation card (columns 11-80; looked for as INCLUDE files are).
    subroutine csv_points(rd, i, name, npts, t, y)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, npts              !! TABLE card image, declared points
        character(len=*), intent(in) :: name        !! table name (messages)
        real(wp), allocatable, intent(out) :: t(:), y(:)
        character(len=:), allocatable :: fname, path, bytes, why
        integer :: stat
        character(len=msglen) :: msg
        fname = trim(adjustl(rd%lines(i + 1)%text(11:80)))
        if (len(fname) == 0) then
            call rd%fail(rd%where(i + 1)//', columns 11-80 (TABLE '//trim(name)//' file): found no file name; '// &
                         'expected the path of a two-column (time, value) file')
            return
        end if
        call rd%read_data_file(i + 1, fname, path, bytes, stat, msg)
        if (stat /= 0) then
            call rd%fail(rd%where(i + 1)//' (TABLE '//trim(name)//' file): '//trim(msg))
            return
        end if
        call read_two_columns(bytes, t, y, stat, why)
        if (stat /= 0) then
            call rd%fail('TABLE '//trim(name)//' ('//rd%where(i)//'), file "'//path//'" '//why)
            return
        end if
        if (size(t) /= npts) then
            call rd%fail(rd%context(i, 2, 'number of points')//': TABLE '//trim(name)//' declares '// &
                         trim(int_str(npts))//' points; its file "'//path//'" has '//trim(int_str(size(t)))// &
                         ' data rows; expected the same number')
            return
        end if
    end subroutine csv_points

    !> INITIAL and PRESCRIB cards. A card for a coordinate the scene locked
    !! is dropped when it only restates the neutral value; otherwise it is an
    !! error.
    subroutine coordinate_cards(rd, cards, cs, bnames, bmap, tabs)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(case_t), intent(inout) :: cs
        character(len=10), intent(in) :: bnames(:)
        type(body_map_t), intent(in) :: bmap
        type(named_table_t), intent(in) :: tabs(:)
        integer :: k, i, kb, m, j, it, stat, ndrop
        real(wp) :: v, vd, fac, amp, freq, phase
        character(len=10) :: s
        character(len=100) :: note

        allocate (cs%x0(cs%model%tree%ndof), cs%xd0(cs%model%tree%ndof))
        cs%x0 = neutral_coordinates(cs%model)
        cs%xd0 = zero
        ndrop = 0
        do k = 1, size(cards)
            i = cards(k)%first
            select case (cards(k)%key)
            case ('INITIAL')
                call active_ref(rd, i, cs, bnames, bmap, kb, m, j, .true.)
                if (rd%failed()) return
                if (j == 0) then
                    call rd%real(i, 3, 'initial value', unit_of(m), v, -unit_limit(m), unit_limit(m), &
                                 default=cs%model%tree%q_ref(m, kb)/unit_factor(m))
                    call rd%real(i, 4, 'initial rate', unit_of(m)//'/s', vd, -1.0e5_wp, 1.0e5_wp, default=zero)
                    if (abs(v*unit_factor(m) - cs%model%tree%q_ref(m, kb)) > 1.0e-12_wp .or. vd /= zero) then
                        call locked_error(rd, i, bnames, bmap, k_old(rd, i, bnames), m)
                        return
                    end if
                    ndrop = ndrop + 1
                    cycle
                end if
                fac = unit_factor(m)
                call rd%real(i, 3, 'initial value', unit_of(m), v, -unit_limit(m), unit_limit(m), &
                             default=cs%model%tree%q_ref(m, kb)/fac)
                call rd%real(i, 4, 'initial rate', unit_of(m)//'/s', vd, -1.0e5_wp, 1.0e5_wp, default=zero)
                cs%x0(j) = v*fac
                cs%xd0(j) = vd*fac
            case ('PRESCRIB')
                call active_ref(rd, i, cs, bnames, bmap, kb, m, j, .true.)
                if (rd%failed()) return
                if (j == 0) then
                    call rd%name(i, 3, 'kind', s)
                    v = cs%model%tree%q_ref(m, kb)/unit_factor(m)
                    if (s == 'CONSTANT') call rd%real(i, 4, 'value', unit_of(m), v, -unit_limit(m), unit_limit(m), &
                                                      default=v)
                    if (rd%failed()) return
                    if (s /= 'CONSTANT' .or. abs(v*unit_factor(m) - cs%model%tree%q_ref(m, kb)) > 1.0e-12_wp) then
                        call locked_error(rd, i, bnames, bmap, k_old(rd, i, bnames), m)
                        return
                    end if
                    ndrop = ndrop + 1
                    cycle
                end if
                fac = unit_factor(m)
                call rd%name(i, 3, 'kind', s)
                if (rd%failed()) return
                select case (s)
                case ('CONSTANT')
                    call rd%real(i, 4, 'value', unit_of(m), v, -unit_limit(m), unit_limit(m), &
                                 default=cs%model%tree%q_ref(m, kb)/fac)
                    cs%model%motion(j) = motion_constant(v*fac)
                case ('ACCEL', 'POSITION')
                    it = table_ref(rd, i, 4, tabs)
                    if (rd%failed()) return
                    if (s == 'ACCEL') then
                        call rd%real(i, 5, 'initial value', unit_of(m), v, -unit_limit(m), unit_limit(m), &
                                     default=cs%model%tree%q_ref(m, kb)/fac)
                        call rd%real(i, 6, 'initial rate', unit_of(m)//'/s', vd, -1.0e5_wp, 1.0e5_wp, default=zero)
                        call motion_accel_table(cs%model%motion(j), tabs(it)%tab%t, tabs(it)%tab%y*fac, &
                                                v*fac, vd*fac, stat)
                    else
                        call motion_position_table(cs%model%motion(j), tabs(it)%tab%t, tabs(it)%tab%y*fac, stat)
                    end if
                case ('HARMONIC')
                    call rd%real(i, 4, 'amplitude', unit_of(m), amp, -unit_limit(m), unit_limit(m))
                    call rd%real(i, 5, 'frequency', 'Hz', freq, zero, 1.0e5_wp)
                    call rd%real(i, 6, 'phase', 'deg', phase, -3600.0_wp, 3600.0_wp, default=zero)
                    cs%model%motion(j) = motion_harmonic(cs%model%tree%q_ref(m, kb), amp*fac, &
                                                         2*acos(-one)*freq, phase*deg)
                case default
                    call rd%fail(rd%context(i, 3, 'kind')//': found "'// &
                                 trim(s)//'"; expected CONSTANT, ACCEL, POSITION or HARMONIC')
                    return
                end select
                if (rd%failed()) return
                cs%model%prescribed(j) = .true.
            end select
        end do
        if (ndrop > 0) then
            write (note, '(i0,a)') ndrop, ' INITIAL/PRESCRIB CARDS DROPPED: THEY HOLD LOCKED COORDINATES AT NEUTRAL'
            call add_scene_note(cs, note)
        end if
    end subroutine coordinate_cards

    !> Append a line to the scene notes of the listing.
    subroutine add_scene_note(cs, text)
        type(case_t), intent(inout) :: cs
        character(len=*), intent(in) :: text
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
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i
        character(len=10), intent(in) :: bnames(:)
        k = body_ref(rd, i, 1, 'body', bnames, .false.)
    end function k_old

    !> Error: card i addresses coordinate m of deck body kold, which a LOCK
    !! or SCENE card locked (named with its location).
    subroutine locked_error(rd, i, bnames, bmap, kold, m)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, kold, m
        character(len=10), intent(in) :: bnames(:)
        type(body_map_t), intent(in) :: bmap
        character(len=:), allocatable :: by
        by = ' (LOCK or SCENE card)'
        if (bmap%locked_by(m, kold) > 0) by = ' by the '//trim(rd%key(bmap%locked_by(m, kold)))//' card at '// &
                                             rd%where(bmap%locked_by(m, kold))
        call rd%fail(rd%context(i, 2, 'coordinate')//': '//trim(bnames(kold))//'.'//coord_names(m)// &
                     ' is locked'//by//'; expected an active coordinate, or the neutral value')
    end subroutine locked_error

    !> Body (in the reduced tree) and coordinate of an INITIAL/PRESCRIB/LIMIT
    !! card (fields F1, F2). A body absorbed by MERGE has no coordinates (an
    !! error). A locked coordinate gives j = 0 when allow_locked, else an error.
    subroutine active_ref(rd, i, cs, bnames, bmap, kb, m, j, allow_locked)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i
        type(case_t), intent(in) :: cs
        character(len=10), intent(in) :: bnames(:)
        type(body_map_t), intent(in) :: bmap
        integer, intent(out) :: kb, m, j
        logical, intent(in) :: allow_locked
        integer :: kold
        j = 0
        kold = body_ref(rd, i, 1, 'body', bnames, .false.)
        m = coord_ref(rd, i, 2)
        kb = 1
        if (rd%failed()) return
        if (bmap%merged_by(kold) > 0) then
            call rd%fail(rd%context(i, 1, 'body')//': body '//trim(bnames(kold))//' was merged by the MERGE card at '// &
                         rd%where(bmap%merged_by(kold))//'; its coordinates no longer exist')
            return
        end if
        kb = bmap%new(kold)
        j = cs%model%tree%dof_index(m, kb)
        if (j == 0 .and. .not. allow_locked) call locked_error(rd, i, bnames, bmap, kold, m)
    end subroutine active_ref

    !> DISC, LIGAMENT, MUSCLE, LIMIT, SPRING, FAMILY cards. Elements are
    !! moved onto merged bodies; an element inside one merged body, or a
    !! joint damper on a locked or merged coordinate, is dropped.
    subroutine element_cards(rd, cards, cs, bnames, bmap, tabs)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(case_t), intent(inout) :: cs
        character(len=10), intent(in) :: bnames(:)
        type(body_map_t), intent(in) :: bmap
        type(named_table_t), intent(in) :: tabs(:)
        integer :: k, i, ninternal, nlimdrop, it
        integer :: nel(nfamilies)       !! elements so far of each family
        integer :: njoint(2)            !! joint-limit dampers and ranges of motion so far
        logical :: keep
        type(disc_family_t) :: df
        type(ligament_family_t) :: lf
        type(muscle_family_t) :: mf
        type(limit_family_t) :: jf
        type(spring_family_t) :: sf
        type(disc_t) :: d
        character(len=100) :: note
        type(ligament_t) :: g
        type(muscle_t) :: mu
        type(spring_t) :: sp

        ninternal = 0
        nlimdrop = 0
        call activation_cards(rd, cards, cs, mf%activations)
        if (rd%failed()) return
        ! room for every element card, trimmed at the end (appending one by one is quadratic)
        allocate (df%items(count(cards%key == 'DISC')), lf%items(count(cards%key == 'LIGAMENT')), &
                  mf%items(count(cards%key == 'MUSCLE' .or. cards%key == 'HILL')), &
                  sf%items(count(cards%key == 'SPRING')), jf%items(count(cards%key == 'LIMIT')), &
                  jf%ranges(count(cards%key == 'ROM')), mf%tables(0))
        nel = 0
        njoint = 0
        do k = 1, size(cards)
            i = cards(k)%first
            select case (cards(k)%key)
            case ('DISC')
                call disc_card(rd, i, bnames, bmap, ninternal, d, keep)
                if (keep) call append(fam_discs)
            case ('LIGAMENT')
                g = ligament_t()
                call line_card(rd, i, 'ligament', g%line_attach_t, i, 7, keep)
                call rd%real(i, 4, 'l1', 'N/m', g%l1, zero, big_modulus)
                call rd%real(i, 5, 'l2', 'N/m^n', g%l2, zero, 1.0e30_wp)
                call rd%real(i, 6, 'exponent n', '-', g%n, one, 10.0_wp, default=2.0_wp)
                if (keep .and. .not. rd%failed()) call append(fam_ligaments)
            case ('MUSCLE')
                mu = muscle_t()
                call line_card(rd, i, 'muscle', mu%line_attach_t, i + 1, 7, keep)
                call rd%real(i, 4, 'stiffness m1', 'N/m', mu%m1, zero, big_modulus)
                call rd%real(i, 5, 'damping m2', 'N s/m', mu%m2, zero, big_modulus)
                call rd%real(i, 6, 'active force Fmax', 'N', mu%fmax, zero, 1.0e6_wp, default=zero)
                if (.not. rd%is_blank(i, 7)) then
                    it = table_ref(rd, i, 7, tabs)
                    if (.not. rd%failed()) then
                        mf%tables = [mf%tables, tabs(it)%tab]
                        mu%activation = size(mf%tables)
                    end if
                end if
                if (keep .and. .not. rd%failed()) call append(fam_muscles)
            case ('HILL')
                mu = muscle_t(law=muscle_hill)
                call line_card(rd, i, 'muscle', mu%line_attach_t, i + 1, 7, keep)
                call rd%real(i, 4, 'maximum isometric force F0', 'N', mu%hill%f0, zero, 1.0e5_wp)
                call rd%real(i, 5, 'optimal fibre length', 'm', mu%hill%lopt, 1.0e-3_wp, one)
                if (.not. rd%is_blank(i, 6)) mu%history = history_ref(rd, i, 6, mf%activations)
                if (mu%history > 0) then
                    mu%hill%srs_q = mf%activations(mu%history)%srs_q
                    mu%hill%srs_range = mf%activations(mu%history)%srs_range
                end if
                call rd%real(i, 7, 'damping', 'N s/m', mu%hill%damping, zero, 1.0e5_wp, default=zero)
                if (keep .and. .not. rd%failed()) call append(fam_muscles)
            case ('SPRING')
                sp = spring_t()
                call line_card(rd, i, 'spring', sp%line_attach_t, i, 6, keep)
                call rd%real(i, 4, 'stiffness', 'N/m', sp%stiffness, zero, big_modulus)
                call rd%real(i, 5, 'damping', 'N s/m', sp%damping, zero, big_modulus, default=zero)
                if (keep .and. .not. rd%failed()) call append(fam_springs)
            case ('LIMIT', 'ROM')
                call joint_card(rd, i, cs, bnames, bmap, nlimdrop, jf, njoint)
            case ('FAMILY')
                call family_card(rd, i, cs)
            end select
            if (rd%failed()) return
        end do
        df%items = df%items(1:nel(fam_discs))
        lf%items = lf%items(1:nel(fam_ligaments))
        mf%items = mf%items(1:nel(fam_muscles))
        jf%items = jf%items(1:njoint(1))
        jf%ranges = jf%ranges(1:njoint(2))
        sf%items = sf%items(1:nel(fam_springs))
        if (ninternal > 0) then
            write (note, '(i0,a)') ninternal, ' ELEMENTS DROPPED: BOTH ENDS ON ONE MERGED BODY'
            call add_scene_note(cs, note)
        end if
        if (nlimdrop > 0) then
            write (note, '(i0,a)') nlimdrop, ' JOINT-LIMIT DAMPERS DROPPED: ON LOCKED OR MERGED COORDINATES'
            call add_scene_note(cs, note)
        end if
        do k = 1, size(cards)
            if (cards(k)%key == 'VIA') call via_card(rd, cards, cards(k)%first, mf%items, bnames, bmap)
            if (rd%failed()) return
        end do
        call model_set_family(cs%model, fam_discs, df)
        call model_set_family(cs%model, fam_ligaments, lf)
        call model_set_family(cs%model, fam_muscles, mf)
        call model_set_family(cs%model, fam_limits, jf)
        call model_set_family(cs%model, fam_springs, sf)
        do k = 1, size(cards)
            if (cards(k)%key == 'SCALE') call scale_card(rd, cards(k)%first, cs)
            if (rd%failed()) return
        end do
    contains
        !> Put the element just read into place nel(f) + 1 of family f's list.
        subroutine append(f)
            integer, intent(in) :: f
            nel(f) = nel(f) + 1
            select case (f)
            case (fam_discs); df%items(nel(f)) = d
            case (fam_ligaments); lf%items(nel(f)) = g
            case (fam_muscles); mf%items(nel(f)) = mu
            case (fam_springs); sf%items(nel(f)) = sp
            end select
        end subroutine append

        !> The attachment of a LIGAMENT, MUSCLE or SPRING card: name (F1),
        !! bodies (F2, F3), points (first continuation card, F1-F6) and free
        !! length (line ll, field lf; blank: the neutral length), moved onto
        !! merged bodies; keep is false for an element inside one merged body.
        subroutine line_card(rd, i, what, at, ll, lf, keep)
            type(deck_reader_t), intent(inout) :: rd
            integer, intent(in) :: i, ll, lf
            character(len=*), intent(in) :: what
            type(line_attach_t), intent(inout) :: at
            logical, intent(out) :: keep
            character(len=10) :: nm
            keep = .false.
            call rd%name(i, 1, what//' name', nm)
            at%name = nm
            at%body_a = body_ref(rd, i, 2, 'body a', bnames, .true.)
            at%body_b = body_ref(rd, i, 3, 'body b', bnames, .true.)
            call distinct_bodies(rd, i, at%body_a, at%body_b)
            call line_points(rd, i + 1, at%point_a, at%point_b)
            select case (what)
            case ('ligament')
                call rd%real(ll, lf, 'slack length', 'm', at%length0, 1.0e-6_wp, big_length, default=-one)
            case ('muscle')
                call rd%real(ll, lf, 'rest length', 'm', at%length0, 1.0e-6_wp, big_length, default=-one)
            case default
                call rd%real(ll, lf, 'free length', 'm', at%length0, zero, big_length, default=-one)
            end select
            if (rd%failed()) return
            call map_ends(bmap, at%body_a, at%point_a, at%body_b, at%point_b, ninternal)
            keep = at%body_a /= at%body_b
        end subroutine line_card
    end subroutine element_cards

    !> VIA muscle body x y z: the next via point of a muscle's path (MUSCLE or
    !! HILL card of that name), in order from body a to body b, moved onto
    !! a merged body as the muscle's ends are; a VIA card of a muscle the
    !! scene dropped is dropped with it.
    subroutine via_card(rd, cards, i, muscles, bnames, bmap)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        integer, intent(in) :: i
        type(muscle_t), intent(inout) :: muscles(:)
        character(len=10), intent(in) :: bnames(:)
        type(body_map_t), intent(in) :: bmap
        character(len=10) :: nm, other
        real(wp) :: p(3)
        integer :: e, kb, f, k
        logical :: defined
        call rd%name(i, 1, 'muscle name', nm)
        kb = body_ref(rd, i, 2, 'body', bnames, .true.)
        do f = 1, 3
            call rd%real(i, 2 + f, 'via point', 'm', p(f), -big_length, big_length)
        end do
        if (rd%failed()) return
        do e = size(muscles), 1, -1       ! (a loop: no temporary of the name component)
            if (muscles(e)%name == nm) exit
        end do
        if (e == 0) then
            defined = .false.
            do k = 1, size(cards)
                if (cards(k)%key /= 'MUSCLE' .and. cards(k)%key /= 'HILL') cycle
                call rd%name(cards(k)%first, 1, 'muscle name', other)
                defined = defined .or. other == nm
            end do
            if (.not. defined) call rd%fail(rd%context(i, 1, 'muscle name')//': found "'//trim(nm)// &
                                            '"; expected the name of a MUSCLE or HILL card')
            return
        end if
        associate (m => muscles(e))
            if (m%nvia == max_via) then
                call rd%fail(rd%context(i, 1, 'muscle name')//': muscle "'//trim(nm)//'" has '// &
                             trim(int_str(max_via))//' via points already; expected at most '// &
                             trim(int_str(max_via))//' VIA cards per muscle')
                return
            end if
            if (kb > 0) then
                p = p + bmap%shift(:, kb)
                kb = bmap%new(kb)
            end if
            m%nvia = m%nvia + 1
            m%via_body(m%nvia) = kb
            m%via_point(:, m%nvia) = p
        end associate
    end subroutine via_card

    !> ACTIVATE cards: the activation histories of Hill-type muscles. A blank
    !! onset is the sled pulse onset: the first time the prescribed
    !! translational acceleration of the root body exceeds 1 g (never, when
    !! it does not).
    subroutine activation_cards(rd, cards, cs, activations)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(case_t), intent(in) :: cs
        type(activation_t), allocatable, intent(out) :: activations(:)
        type(activation_t) :: ah
        integer :: k, i
        allocate (activations(0))
        do k = 1, size(cards)
            if (cards(k)%key /= 'ACTIVATE') cycle
            i = cards(k)%first
            ah = activation_t()
            call rd%name(i, 1, 'history name', ah%name)
            if (rd%failed()) return
            call rd%real(i, 2, 'pre-activation u0', '-', ah%u0, zero, one)
            call rd%real(i, 3, 'reflex activation u1', '-', ah%u1, zero, one)
            if (rd%is_blank(i, 4)) then
                ah%t_onset = pulse_onset(cs)
            else
                call rd%real(i, 4, 'pulse onset', 's', ah%t_onset, -1.0e4_wp, 1.0e4_wp)
            end if
            call rd%real(i, 5, 'reflex delay', 's', ah%delay, zero, 10.0_wp)
            call rd%real(i, 6, 'rise time', 's', ah%rise, zero, 10.0_wp, default=zero)
            call rd%real(i + 1, 1, 'activation time constant', 's', ah%tau_act, 1.0e-4_wp, 10.0_wp, default=0.015_wp)
            call rd%real(i + 1, 2, 'deactivation time constant', 's', ah%tau_deact, 1.0e-4_wp, 10.0_wp, &
                         default=0.05_wp)
            call rd%real(i + 1, 3, 'short-range stiffness q', '-', ah%srs_q, zero, 1.0e3_wp, default=zero)
            call rd%real(i + 1, 4, 'short-range stiffness range', 'lopt', ah%srs_range, 1.0e-4_wp, one, &
                         default=0.01_wp)
            if (rd%failed()) return
            activations = [activations, ah]
        end do
    end subroutine activation_cards

    !> First time (on a 0.1 ms grid) the prescribed translational
    !! acceleration of the root body exceeds 1 g; huge when it never does.
    function pulse_onset(cs) result(t0)
        type(case_t), intent(in) :: cs
        real(wp) :: t0, t, a(3), x, xd
        integer :: root, m, j, n
        t0 = huge(one)
        root = findloc(cs%model%tree%parent, 0, dim=1)
        do n = 0, nint((cs%t_end - cs%t_start)/1.0e-4_wp)
            t = cs%t_start + n*1.0e-4_wp
            a = zero
            do m = 1, 3
                j = cs%model%tree%dof_index(m, root)
                if (j == 0) cycle
                if (cs%model%prescribed(j)) call motion_eval(cs%model%motion(j), t, x, xd, a(m))
            end do
            if (norm3(a) > g_std) then
                t0 = t
                return
            end if
        end do
    end function pulse_onset

    !> Activation history named in field f (an ACTIVATE card).
    integer function history_ref(rd, i, f, hist) result(ih)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, f
        type(activation_t), intent(in) :: hist(:)
        character(len=10) :: s
        ih = 0
        call rd%name(i, f, 'activation history', s)
        if (rd%failed()) return
        do ih = size(hist), 1, -1
            if (hist(ih)%name == s) exit
        end do
        if (ih == 0) call rd%fail(rd%context(i, f, 'activation history')//': found "'//trim(s)// &
                                  '"; expected the name of an ACTIVATE card')
    end function history_ref

    !> Old body numbers and points -> reduced tree (MERGE); counts the
    !! elements with both ends on one merged body.
    pure subroutine map_ends(bmap, ka, pa, kb, pb, ninternal)
        type(body_map_t), intent(in) :: bmap
        integer, intent(inout) :: ka, kb
        real(wp), intent(inout) :: pa(3), pb(3)
        integer, intent(inout) :: ninternal
        if (ka > 0) then
            pa = pa + bmap%shift(:, ka)
            ka = bmap%new(ka)
        end if
        if (kb > 0) then
            pb = pb + bmap%shift(:, kb)
            kb = bmap%new(kb)
        end if
        if (ka == kb) ninternal = ninternal + 1
    end subroutine map_ends

    !> A DISC card and its two continuation cards; keep is false for a disc
    !! inside one merged body.
    subroutine disc_card(rd, i, bnames, bmap, ninternal, d, keep)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i
        character(len=10), intent(in) :: bnames(:)
        type(body_map_t), intent(in) :: bmap
        integer, intent(inout) :: ninternal
        type(disc_t), intent(out) :: d
        logical, intent(out) :: keep
        integer :: f
        real(wp) :: v
        d = disc_t()
        call rd%name(i, 1, 'disc name', d%name)
        d%body_a = body_ref(rd, i, 2, 'lower body', bnames, .false.)
        d%body_b = body_ref(rd, i, 3, 'upper body', bnames, .false.)
        call distinct_bodies(rd, i, d%body_a, d%body_b)
        call rd%real(i, 4, 'area A', 'm^2', d%area, 1.0e-8_wp, 1.0_wp)
        call rd%real(i, 5, 'thickness h', 'm', d%h, 1.0e-5_wp, 1.0_wp)
        call rd%real(i, 6, 'modulus d1', 'Pa', d%d1, 1.0e-3_wp, big_modulus)
        call rd%real(i, 7, 'viscous modulus d2', 'Pa s', d%d2, zero, big_modulus)
        do f = 1, 3
            call rd%real(i + 1, f, 'lower plate centre', 'm', d%pa(f), -big_length, big_length)
            call rd%real(i + 1, 3 + f, 'upper plate centre', 'm', d%pb(f), -big_length, big_length)
        end do
        call rd%real(i + 1, 7, 'plate tilt', 'deg', v, -90.0_wp, 90.0_wp, default=zero)
        d%tilt = v*deg
        call rd%real(i + 2, 1, 'shear modulus G', 'Pa', d%g, 1.0e-3_wp, big_modulus)
        call rd%real(i + 2, 2, 'second moment Ix', 'm^4', d%ix, 1.0e-20_wp, one)
        call rd%real(i + 2, 3, 'second moment Iy', 'm^4', d%iy, 1.0e-20_wp, one)
        call rd%real(i + 2, 4, 'torsion constant J', 'm^4', d%j, 1.0e-20_wp, one)
        call rd%real(i + 2, 5, 'shear factor k', '-', d%kshear, 0.1_wp, 10.0_wp, default=1.2_wp)
        call rd%real(i + 2, 6, 'viscous modulus d2b of shear, bending and torsion', 'Pa s', d%d2b, zero, &
                     big_modulus, default=d%d2)
        call rd%real(i + 2, 7, 'axial stiffness in tension as a fraction of d1''s', '-', d%ft, 1.0e-3_wp, one, &
                     default=one)
        if (rd%failed()) return
        call map_ends(bmap, d%body_a, d%pa, d%body_b, d%pb, ninternal)
        keep = d%body_a /= d%body_b
    end subroutine disc_card

    !> A LIMIT card (one-way joint-limit damper) or a ROM card (resistance
    !! beyond the physiological range: rotation, range (deg), stiffness at the
    !! edge K [N m/rad], excess t0 [deg] over which it grows e-fold); dropped
    !! on a locked or merged coordinate.
    subroutine joint_card(rd, i, cs, bnames, bmap, ndrop, jf, nel)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i
        type(case_t), intent(inout) :: cs
        character(len=10), intent(in) :: bnames(:)
        type(body_map_t), intent(in) :: bmap
        integer, intent(inout) :: ndrop
        type(limit_family_t), intent(inout) :: jf     !! the dampers and ranges read so far
        integer, intent(inout) :: nel(2)              !! how many dampers and ranges
        type(joint_limit_t) :: lim
        type(joint_range_t) :: r
        integer :: kb, m, j
        ! a body absorbed by MERGE or a locked coordinate: the element would do nothing
        if (bmap%merged_by(body_ref(rd, i, 1, 'body', bnames, .false.)) > 0) then
            ndrop = ndrop + 1
            return
        end if
        call active_ref(rd, i, cs, bnames, bmap, kb, m, j, .true.)
        if (rd%failed()) return
        if (j == 0) then
            ndrop = ndrop + 1
            return
        end if
        if (rd%key(i) == 'LIMIT') then
            lim = joint_limit_t()
            lim%body = kb; lim%local = m; lim%dof = j
            call rd%real(i, 3, 'lower limit', unit_of(m), lim%xmin, -unit_limit(m), unit_limit(m))
            call rd%real(i, 4, 'upper limit', unit_of(m), lim%xmax, -unit_limit(m), unit_limit(m))
            if (.not. rd%failed() .and. .not. (lim%xmax > lim%xmin)) then
                call rd%fail(rd%context(i, 4, 'upper limit')//': found '// &
                             trim(rd%raw(i, 4))//'; expected a value above the lower limit '//trim(rd%raw(i, 3)))
                return
            end if
            call rd%real(i, 5, 'damping C0', 'N s/m or N m s/rad', lim%c0, zero, big_modulus)
            call rd%real(i, 6, 'damping ramp C1', 'per m or per rad of excess', lim%c1, zero, big_modulus)
            call rd%real(i, 7, 'neutral value', unit_of(m), lim%xneutral, lim%xmin, lim%xmax, &
                         default=max(lim%xmin, min(lim%xmax, cs%model%tree%q_ref(m, kb)/unit_factor(m))))
            lim%xmin = lim%xmin*unit_factor(m)
            lim%xmax = lim%xmax*unit_factor(m)
            lim%xneutral = lim%xneutral*unit_factor(m)
            if (rd%failed()) return
            nel(1) = nel(1) + 1; jf%items(nel(1)) = lim
            return
        end if
        if (m <= 3) then
            call rd%fail(rd%context(i, 2, 'coordinate')//': found '//coord_names(m)//'; expected a rotation '// &
                         '(RX, RY or RZ): ROM cards hold joint rotations')
            return
        end if
        r%dof = j
        r%label = trim(cs%model%tree%name(kb))//' '//coord_names(m)
        call rd%real(i, 3, 'lower end of range', 'deg', r%xmin, -180.0_wp, 180.0_wp)
        call rd%real(i, 4, 'upper end of range', 'deg', r%xmax, -180.0_wp, 180.0_wp)
        if (.not. rd%failed() .and. .not. (r%xmax > r%xmin)) then
            call rd%fail(rd%context(i, 4, 'upper end of range')//': found '//trim(rd%raw(i, 4))// &
                         '; expected a value above the lower end '//trim(rd%raw(i, 3)))
            return
        end if
        call rd%real(i, 5, 'stiffness at the edge K', 'N m/rad', r%k, zero, big_modulus)
        call rd%real(i, 6, 'e-fold excess t0', 'deg', r%t0, 0.01_wp, 90.0_wp, default=5.0_wp)
        if (rd%failed()) return
        r%xmin = r%xmin*deg; r%xmax = r%xmax*deg; r%t0 = r%t0*deg
        nel(2) = nel(2) + 1; jf%ranges(nel(2)) = r
    end subroutine joint_card


    !> SCALE name family item factor: multiply one property of every element
    !! of a family (the items of a sweep's FAMILY parameters), after every
    !! element card; the named factors a calibration fits (FIELD4 SCALE name).
    subroutine scale_card(rd, i, cs)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i
        type(case_t), intent(inout) :: cs
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

    !> Element family named s in field F2 of line i (an error when unknown).
    integer function family_ref(rd, i, s) result(fam)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i
        character(len=*), intent(in) :: s
        fam = 0
        if (rd%failed()) return
        fam = family_index(s)
        if (fam == 0) call rd%fail(rd%context(i, 2, 'element family')//': found "'//trim(s)//'"; expected one of '// &
                                   join(family_name))
    end function family_ref

    !> FAMILY name ON|OFF: switch an element family.
    subroutine family_card(rd, i, cs)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i
        type(case_t), intent(inout) :: cs
        integer :: fam
        character(len=10) :: s
        character(len=100) :: note
        call rd%name(i, 1, 'element family', s)
        if (rd%failed()) return
        fam = family_index(s)
        if (fam == 0) then
            call rd%fail(rd%context(i, 1, 'element family')//': found "'// &
                         trim(s)//'"; expected one of '//join(family_name))
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

    !> FORCE and COUPLE cards (moved onto merged bodies).
    subroutine load_cards(rd, cards, cs, bnames, bmap, tabs)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(case_t), intent(inout) :: cs
        character(len=10), intent(in) :: bnames(:)
        type(body_map_t), intent(in) :: bmap
        type(named_table_t), intent(in) :: tabs(:)
        type(applied_load_t) :: al
        integer :: k, i, f, it, nal
        character(len=10) :: s
        deallocate (cs%model%applied)
        allocate (cs%model%applied(count(cards%key == 'FORCE' .or. cards%key == 'COUPLE')))
        nal = 0
        do k = 1, size(cards)
            if (cards(k)%key /= 'FORCE' .and. cards(k)%key /= 'COUPLE') cycle
            i = cards(k)%first
            al = applied_load_t()
            al%kind = merge(applied_force, applied_couple, cards(k)%key == 'FORCE')
            al%body = body_ref(rd, i, 1, 'body', bnames, .false.)
            call rd%name(i, 2, 'frame', s)
            if (rd%failed()) return
            select case (s)
            case ('R', 'INERTIAL'); al%frame = frame_inertial
            case ('BODY'); al%frame = frame_body
            case default
                call rd%fail(rd%context(i, 2, 'frame')//': found "'//trim(s)//'"; expected R (inertial) or BODY')
                return
            end select
            it = table_ref(rd, i, 3, tabs)
            do f = 1, 3
                call rd%real(i, 3 + f, 'direction', '-', al%direction(f), -1.0e6_wp, 1.0e6_wp)
            end do
            if (rd%failed()) return
            if (norm3(al%direction) == zero) then
                call rd%fail(rd%where(i)//', columns 41-70 ('//trim(cards(k)%key)//' card, fields F4-F6 '// &
                             '''direction''): found a zero vector; expected a direction')
                return
            end if
            al%direction = al%direction/norm3(al%direction)
            al%magnitude = tabs(it)%tab
            if (al%kind == applied_force) then
                do f = 1, 3
                    call rd%real(i + 1, f, 'point of application', 'm', al%point(f), -big_length, big_length)
                end do
            end if
            if (rd%failed()) return
            al%point = al%point + bmap%shift(:, al%body)
            al%body = bmap%new(al%body)
            nal = nal + 1; cs%model%applied(nal) = al
        end do
        cs%model%applied = cs%model%applied(1:nal)
    end subroutine load_cards

    !> STIFFEN factor [family]: multiply element stiffnesses (disc d1, d2 and
    !! G, ligament l1 and l2, muscle m1, spring stiffness) by a factor, for
    !! every family or the one named; damping-to-stiffness ratios of the discs
    !! are kept.
    subroutine stiffen_cards(rd, cards, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(case_t), intent(inout) :: cs
        integer :: k, i, fam, f
        real(wp) :: fac
        character(len=10) :: s
        do k = 1, size(cards)
            if (cards(k)%key /= 'STIFFEN') cycle
            i = cards(k)%first
            call rd%real(i, 1, 'stiffness factor', '-', fac, 1.0e-6_wp, 1.0e6_wp)
            call rd%name(i, 2, 'element family', s, optional_blank=.true.)
            if (rd%failed()) return
            fam = 0
            if (len_trim(s) > 0) fam = family_ref(rd, i, s)
            if (rd%failed()) return
            do f = 1, size(cs%model%family)
                if (fam == 0 .or. fam == f) call cs%model%family(f)%f%stiffen(fac)
            end do
        end do
    end subroutine stiffen_cards

    !> HEADNECK: the bodies reported as head and T1 (their merged bodies
    !! when MERGE absorbed them).
    subroutine report_cards(rd, cards, cs, bnames, bmap)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        type(case_t), intent(inout) :: cs
        character(len=10), intent(in) :: bnames(:)
        type(body_map_t), intent(in) :: bmap
        integer :: ic
        cs%head = findloc(bnames, 'HEAD', dim=1)
        if (cs%head == 0) cs%head = size(bnames)
        cs%head = bmap%new(cs%head)
        cs%t1 = findloc(cs%model%tree%parent, 0, dim=1)
        ic = single(rd, cards, 'HEADNECK', .false.)
        if (ic > 0) then
            cs%head = bmap%new(body_ref(rd, cards(ic)%first, 1, 'head body', bnames, .false.))
            if (.not. rd%is_blank(cards(ic)%first, 2)) &
                cs%t1 = bmap%new(body_ref(rd, cards(ic)%first, 2, 'T1 body', bnames, .false.))
        end if
        ic = single(rd, cards, 'CRITERIA', .false.)
        if (ic > 0) call criteria_card(rd, cards(ic)%first, cs)
    end subroutine report_cards

    !> Attachment points on a continuation card: F1-F3 on body a, F4-F6 on body b.
    subroutine line_points(rd, i, pa, pb)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i
        real(wp), intent(out) :: pa(3), pb(3)
        integer :: f
        do f = 1, 3
            call rd%real(i, f, 'point on body a', 'm', pa(f), -big_length, big_length)
            call rd%real(i, 3 + f, 'point on body b', 'm', pb(f), -big_length, big_length)
        end do
    end subroutine line_points

    subroutine distinct_bodies(rd, i, ka, kb)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, ka, kb
        if (rd%failed()) return
        if (ka == kb) call rd%fail(rd%where(i)//', columns 21-40 ('//trim(rd%key(i))//' card, fields F2-F3): '// &
                                   'both ends on the same body; expected two different bodies')
    end subroutine distinct_bodies

    !> Body named in field f (R allowed when allow_inertial: returns 0).
    integer function body_ref(rd, i, f, what, bnames, allow_inertial) result(kb)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, f
        character(len=*), intent(in) :: what
        character(len=10), intent(in) :: bnames(:)
        logical, intent(in) :: allow_inertial
        character(len=10) :: s
        kb = 1
        call rd%name(i, f, what, s)
        if (rd%failed()) return
        if (allow_inertial .and. (s == 'R' .or. s == 'INERTIAL')) then
            kb = 0
            return
        end if
        kb = findloc(bnames, s, dim=1)
        if (kb == 0) then
            call rd%fail(rd%context(i, f, what)//': found "'//trim(s)//'"; expected a body defined '// &
                         'on a BODY card'//merge(' or R', '     ', allow_inertial))
            kb = 1
        end if
    end function body_ref

    !> Coordinate named in field f: TX TY TZ RX RY RZ -> 1..6.
    integer function coord_ref(rd, i, f) result(m)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, f
        character(len=10) :: s
        m = 1
        call rd%name(i, f, 'coordinate', s)
        if (rd%failed()) return
        m = findloc(coord_names, s(1:2), dim=1)
        if (m == 0 .or. len_trim(s) /= 2) then
            call rd%fail(rd%context(i, f, 'coordinate')//': found "'//trim(s)//'"; expected TX TY TZ RX RY or RZ')
            m = 1
        end if
    end function coord_ref

    !> Table named in field f.
    integer function table_ref(rd, i, f, tabs) result(it)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, f
        type(named_table_t), intent(in) :: tabs(:)
        character(len=10) :: s
        integer :: k
        it = 1
        call rd%name(i, f, 'table', s)
        if (rd%failed()) return
        it = 0
        do k = 1, size(tabs)
            if (tabs(k)%name == s) it = k
        end do
        if (it == 0) then
            call rd%fail(rd%context(i, f, 'table')//': found "'//trim(s)//'"; expected the name of a TABLE or PULSE card')
            it = 1
        end if
    end function table_ref

    !> Deck unit of coordinate m and its factor to SI.
    pure function unit_of(m) result(u)
        integer, intent(in) :: m
        character(len=3) :: u
        u = merge('m  ', 'deg', m <= 3)
    end function unit_of

    pure real(wp) function unit_factor(m) result(f)
        integer, intent(in) :: m
        f = merge(one, deg, m <= 3)
    end function unit_factor

    !> Largest magnitude accepted for a coordinate value in deck units.
    pure real(wp) function unit_limit(m) result(f)
        integer, intent(in) :: m
        f = merge(big_length, 3600.0_wp, m <= 3)
    end function unit_limit

    pure function join(list) result(s)
        character(len=*), intent(in) :: list(:)
        character(len=:), allocatable :: s
        integer :: k
        s = trim(list(1))
        do k = 2, size(list)
            s = s//' '//trim(list(k))
        end do
    end function join

    pure function real_str(v) result(s)
        real(wp), intent(in) :: v
        character(len=24) :: s
        write (s, '(g0.6)') v
    end function real_str

end module hn_deck
