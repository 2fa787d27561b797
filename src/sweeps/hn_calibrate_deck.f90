!> The calibration deck's cards (docs/sweeps.md): each card read into the
!! calibration (hn_calibrate_types) with its located checks, then the
!! checks across cards; the binding of the cases to their decks and data
!! is hn_calibrate_cases'.
module hn_calibrate_deck
    use hn_kinds, only: wp, zero, one
    use hn_case, only: deck_line_t
    use hn_deck_reader, only: deck_reader_t, read_card_images, int_str, upper
    use hn_card_engine, only: card_deck_t, deck_format_t, deck_card_t, read_deck_cards, any_times, exactly_once
    use hn_deck_state, only: real_str
    use hn_rating, only: peak_t
    use hn_volunteer_data, only: data_channel_t
    use hn_calibrate_types, only: calibration_t, calibration_deck_t, calibration_reading_t, metric_iso18571
    use hn_calibrate_case_cards, only: read_case_card, read_data_card, read_rated_card, read_standing_card
    implicit none
    private

    public :: read_calibration_cards, read_cfc_class, columns

    integer, parameter :: peak_name_len = 16                 !! longest peak name (PEAK card, columns 51-80)

contains

    !> The cards of a calibration deck: TITLE; CASE path (columns 11-70) [weight
    !! (F7, default 1)] followed by DATA, the directory of that case's
    !! volunteers, a reference CSV (a name ending in .csv) or a CSV of
    !! published peaks (its header peak,mean,sd[,time_mean,time_sd]), then for a
    !! reference case optional RATED cards (CSV column, model channel,
    !! [scale], [subtracted channel], [START], [SAMPLES]); FIT NELDER max-evaluations
    !! starting-points seed [peak-weight [peak-time-weight [peak-margin]]];
    !! RATING window-start window-end CFC-class peak-time-tolerance
    !! [CORA or ISO18571]; CHANNEL
    !! cards (channel, VALUE or RATE, [DEG-RAD], the file in columns
    !! 41-80); PEAK cards (channel, MIN or MAX, window start and end, the
    !! name in columns 51-80); PARAM cards as in a sweep deck; optional
    !! OPTIONAL cards (up to 7 PARAM names each: bound in the cases whose
    !! deck has their target, left out of the others); optional
    !! PASSIVE [limit] (a set whose neck stands without its muscles is not
    !! run); optional RANGES weight [margin] (the joints past their ranges in J);
    !! optional STANDING deck bound (a run at rest judging standing);
    !! optional VALUES cards (up to 7 values each, in PARAM order), the
    !! point scored when max-evaluations is 0 (default: the decks' own
    !! values), else a starting point tried before the LHS points; optional CURVES file (columns 11-80: the rated curves of
    !! that point written as CSV); its cases are bound to their decks and data by
    !! hn_calibrate_cases (docs/sweeps.md).
    subroutine read_calibration_cards(path, source, cal, st, include_path)
        character(len=*), intent(in) :: path     !! the calibration deck's file
        character(len=*), intent(in) :: source   !! its name in messages
        type(calibration_t), intent(out) :: cal  !! the calibration, its cases not yet bound
        type(calibration_deck_t), intent(out) :: st  !! the deck and its cards; st%rd%stat, st%rd%errmsg: the first error
        character(len=*), intent(in), optional :: include_path(:)  !! directories searched for CASE decks and INCLUDE files
        type(calibration_reading_t) :: r
        r%rd%top = source
        if (present(include_path)) r%rd%search = include_path
        call read_card_images(r%rd, path, source, 0)
        allocate (r%cal%decks(0), r%cal%data(0), r%cal%values(0), r%cal%channels(0), r%cal%peaks(0), r%cal%weight(0), &
                  r%cal%stand(0))
        allocate (r%params(0), r%optional(0), r%optional_line(0), r%channel_line(0), r%peak_line(0), &
                  r%data_line(0), r%peak_channel(0), r%rated_line(0), r%rated_case(0), r%is_ref(0), r%is_pub(0))
        call read_deck_cards(r, calibration_format())
        call check_calibration_cards(r%calibration_deck_t, r%cal, source)
        st = r%calibration_deck_t
        cal = r%cal
    end subroutine read_calibration_cards

    !> The calibration deck's cards for the card engine (docs/sweeps.md):
    !! the study's here, the cases' in hn_calibrate_case_cards.
    function calibration_format() result(fmt)
        type(deck_format_t) :: fmt
        fmt%name = 'calibration'
        fmt%doc = 'docs/sweeps.md'
        fmt%title_first = .false.
        allocate (fmt%cards, source=[deck_card_t('TITLE', 0, any_times, read_title_card), &
                                     deck_card_t('CASE', 0, any_times, read_case_card), &
                                     deck_card_t('DATA', 0, any_times, read_data_card), &
                                     deck_card_t('RATED', 0, any_times, read_rated_card), &
                                     deck_card_t('FIT', 0, exactly_once, read_fit_card), &
                                     deck_card_t('RATING', 0, exactly_once, read_rating_card), &
                                     deck_card_t('CHANNEL', 0, any_times, read_channel_card), &
                                     deck_card_t('PEAK', 0, any_times, read_peak_card), &
                                     deck_card_t('PARAM', 0, any_times, read_param_card), &
                                     deck_card_t('OPTIONAL', 0, any_times, read_optional_card), &
                                     deck_card_t('PASSIVE', 0, any_times, read_passive_card), &
                                     deck_card_t('STANDING', 0, any_times, read_standing_card), &
                                     deck_card_t('RETURN', 0, any_times, read_standing_card), &
                                     deck_card_t('REST', 0, any_times, read_standing_card), &
                                     deck_card_t('RANGES', 0, any_times, read_ranges_card), &
                                     deck_card_t('VALUES', 0, any_times, read_values_card), &
                                     deck_card_t('CURVES', 0, any_times, read_curves_card)])
    end function calibration_format

    !> TITLE: the calibration's title (columns 11-80).
    subroutine read_title_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                       !! the card's line
        select type (st => deck)
        type is (calibration_reading_t)
            st%cal%title = adjustl(st%rd%lines(i)%text(11:80))
        end select
    end subroutine read_title_card

    !> A channel frequency class of SAE J211/1 (60, 180, 600 or 1000 Hz)
    !! in field f of card i, as a real [Hz]; anything else fails the
    !! reader with the card's line and columns.
    subroutine read_cfc_class(rd, i, f, cfc)
        type(deck_reader_t), intent(inout) :: rd  !! the deck's reader
        integer, intent(in) :: i                  !! the card's line
        integer, intent(in) :: f                  !! the field
        real(wp), intent(out) :: cfc              !! the class [Hz]
        integer :: k
        k = 0
        call rd%int(i, f, 'CFC class', k, 1, 100000)
        if (.not. rd%failed() .and. all(k /= [60, 180, 600, 1000])) &
            call rd%fail(rd%context(i, f, 'CFC class')//': found '//trim(rd%raw(i, f))// &
                         '; expected 60, 180, 600 or 1000 (SAE J211/1)')
        cfc = real(k, wp)
    end subroutine read_cfc_class

    !> FIT NELDER max-evaluations starting-points seed [peak-weight
    !! [peak-time-weight [peak-margin]]]: one card.
    subroutine read_fit_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                       !! the card's line
        character(len=10) :: s
        select type (st => deck)
        type is (calibration_reading_t)
            associate (cal => st%cal, rd => st%rd)
                call rd%name(i, 1, 'optimizer', s)
                if (s /= 'NELDER' .and. .not. rd%failed()) call rd%fail(rd%context(i, 1, 'optimizer')// &
                                                                       ': found "'//trim(s)//'"; expected NELDER')
                call rd%int(i, 2, 'maximum evaluations', cal%max_evals, 0, 100000)
                call rd%int(i, 3, 'starting points', cal%nstart, 2, 10000)
                call rd%int(i, 4, 'seed', cal%seed, 1, 2147483646)
                call rd%real(i, 5, 'peak weight', '-', cal%peak_weight, zero, 1.0e3_wp, default=0.02_wp)
                call rd%real(i, 6, 'peak-time weight', '-', cal%time_weight, zero, 1.0e3_wp, default=zero)
                call rd%real(i, 7, 'peak margin', 'SD', cal%peak_margin, zero, 0.9_wp, default=zero)
            end associate
        end select
    end subroutine read_fit_card

    !> RATING window-start window-end CFC-class peak-time-tolerance [CORA
    !! or ISO18571]: one card.
    subroutine read_rating_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                       !! the card's line
        character(len=10) :: opt
        select type (st => deck)
        type is (calibration_reading_t)
            associate (cal => st%cal, rd => st%rd)
                st%rating_line = i
                call rd%real(i, 1, 'window start', 'ms', cal%window(1), zero, 1.0e6_wp)
                call rd%real(i, 2, 'window end', 'ms', cal%window(2), zero, 1.0e6_wp)
                if (.not. rd%failed() .and. .not. cal%window(2) > cal%window(1)) &
                    call rd%fail(rd%context(i, 2, 'window end')//': found '//trim(rd%raw(i, 2))// &
                                 ' ms; expected a time after the window start '//trim(rd%raw(i, 1))//' ms')
                call read_cfc_class(rd, i, 3, cal%cfc)
                call rd%real(i, 4, 'peak-time tolerance', 'ms', cal%time_tolerance, 1.0e-3_wp, 1.0e6_wp)
                if (.not. rd%failed() .and. .not. rd%is_blank(i, 5)) then
                    call rd%choice(i, 5, 'metric', [character(len=10) :: 'CORA', 'ISO18571'], opt)
                    if (opt == 'ISO18571') cal%metric = metric_iso18571
                end if
            end associate
        end select
    end subroutine read_rating_card

    !> CHANNEL channel VALUE-or-RATE [DEG-RAD] file (columns 41-80): a
    !! rated channel, one card per channel.
    subroutine read_channel_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                       !! the card's line
        type(data_channel_t) :: dc
        character(len=10) :: opt
        integer :: k
        select type (st => deck)
        type is (calibration_reading_t)
            associate (cal => st%cal, rd => st%rd)
                dc = data_channel_t()
                call rd%name(i, 1, 'channel', dc%name)
                call rd%choice(i, 2, 'from the file', [character(len=10) :: 'VALUE', 'RATE'], opt)
                dc%derivative = opt == 'RATE'
                if (.not. rd%failed() .and. .not. rd%is_blank(i, 3)) then
                    call rd%choice(i, 3, 'conversion', [character(len=10) :: 'DEG-RAD'], opt)
                    dc%deg_to_rad = .true.
                end if
                dc%file = rd%text(i, 41)
                if (.not. rd%failed() .and. len_trim(dc%file) == 0) &
                    call rd%fail(columns(rd, i, 41, 'data file')//': found a blank; expected the name of the file '// &
                                 'of the channel''s runs in each DATA directory')
                if (rd%failed()) return
                k = channel_number(cal, dc%name)
                if (k > 0) then
                    call rd%fail(rd%context(i, 1, 'channel')//': found "'//trim(dc%name)//'" again; expected '// &
                                 'one CHANNEL card per channel (the CHANNEL card at '// &
                                 rd%where(st%channel_line(k))//' has it)')
                    return
                end if
                cal%channels = [cal%channels, dc]
                st%channel_line = [st%channel_line, i]
            end associate
        end select
    end subroutine read_channel_card

    !> PEAK channel MIN-or-MAX window-start window-end name (columns
    !! 51-80): a peak, one card per name; its channel, a CHANNEL card's
    !! before or after it, is found by check_calibration_cards.
    subroutine read_peak_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                       !! the card's line
        type(peak_t) :: pk
        character(len=10) :: s, opt
        character(len=:), allocatable :: ctext
        integer :: k
        select type (st => deck)
        type is (calibration_reading_t)
            associate (cal => st%cal, rd => st%rd)
                pk = peak_t()
                call rd%name(i, 1, 'channel', s)
                call rd%choice(i, 2, 'extreme', [character(len=10) :: 'MIN', 'MAX'], opt)
                pk%sign = merge(-one, one, opt == 'MIN')
                call rd%real(i, 3, 'window start', 'ms', pk%window(1), zero, 1.0e6_wp)
                call rd%real(i, 4, 'window end', 'ms', pk%window(2), zero, 1.0e6_wp)
                if (.not. rd%failed() .and. .not. pk%window(2) > pk%window(1)) &
                    call rd%fail(rd%context(i, 4, 'window end')//': found '//trim(rd%raw(i, 4))// &
                                 ' ms; expected a time after the window start '//trim(rd%raw(i, 3))//' ms')
                ctext = rd%text(i, 51)
                if (.not. rd%failed() .and. (len(ctext) == 0 .or. len(ctext) > peak_name_len)) &
                    call rd%fail(columns(rd, i, 51, 'peak name')//': found "'//ctext//'"; expected a name of 1 to '// &
                                 trim(int_str(peak_name_len))//' characters')
                if (rd%failed()) return
                pk%name = ctext
                k = peak_number(cal, pk%name)
                if (k > 0) then
                    call rd%fail(columns(rd, i, 51, 'peak name')//': found "'//trim(pk%name)//'" again; expected '// &
                                 'one PEAK card per name (the PEAK card at '//rd%where(st%peak_line(k))//' has it)')
                    return
                end if
                cal%peaks = [cal%peaks, pk]
                st%peak_line = [st%peak_line, i]
                st%peak_channel = [character(len=10) :: st%peak_channel, s]
            end associate
        end select
    end subroutine read_peak_card

    !> PARAM: a fitted parameter, kept for each case's sweep (bind_cases).
    subroutine read_param_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                       !! the card's line
        select type (st => deck)
        type is (calibration_reading_t)
            st%params = [st%params, st%rd%lines(i)]
        end select
    end subroutine read_param_card

    !> The OPTIONAL card: up to 7 PARAM names (F1-F7), each bound in the cases whose
    !! deck has its target (family, body or card) and left out of the
    !! others, e.g. the muscles' parameters beside segment cases that have
    !! no muscles; every one must be bound in some case (bind_cases).
    subroutine read_optional_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                       !! the card's line
        character(len=10) :: name
        integer :: f
        select type (st => deck)
        type is (calibration_reading_t)
            do f = 1, 7
                if (st%rd%is_blank(i, f)) cycle
                call st%rd%name(i, f, 'parameter name', name)
                if (st%rd%failed()) return
                if (any(st%optional == name)) then
                    call st%rd%fail(st%rd%context(i, f, 'parameter name')//': found "'//trim(name)// &
                                    '" a second time on the OPTIONAL cards; expected each parameter once')
                    return
                end if
                st%optional = [character(len=10) :: st%optional, name]
                st%optional_line = [st%optional_line, i]
            end do
            if (.not. any(st%optional_line == i)) &
                call st%rd%fail(st%rd%context(i, 1, 'parameter name')//': found no name; expected the PARAM '// &
                                'names bound only in the cases that have their target')
        end select
    end subroutine read_optional_card

    !> PASSIVE [limit]: a set whose neck stands without its muscles is not run.
    subroutine read_passive_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                       !! the card's line
        select type (st => deck)
        type is (calibration_reading_t)
            associate (cal => st%cal)
                cal%passive = .true.
                call st%rd%real(i, 1, 'largest real part at rest without muscles', '1/s', cal%passive_limit, &
                                -100.0_wp, 100.0_wp, default=zero)
            end associate
        end select
    end subroutine read_passive_card

    !> RANGES weight [margin]: the joints past their ranges in J.
    subroutine read_ranges_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                       !! the card's line
        select type (st => deck)
        type is (calibration_reading_t)
            associate (cal => st%cal)
                call st%rd%real(i, 1, 'range weight', '-', cal%range_weight, zero, 1.0e3_wp)
                call st%rd%real(i, 2, 'range margin', '-', cal%range_inside, zero, 0.9_wp, default=zero)
            end associate
        end select
    end subroutine read_ranges_card

    !> The VALUES card: up to 7 parameter values, in PARAM order (their count:
    !! check_calibration_cards).
    subroutine read_values_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                       !! the card's line
        integer :: f
        real(wp) :: x
        select type (st => deck)
        type is (calibration_reading_t)
            associate (cal => st%cal)
                if (st%values_line == 0) st%values_line = i
                do f = 1, 7
                    if (st%rd%is_blank(i, f)) cycle
                    call st%rd%real(i, f, 'parameter value', '-', x, -1.0e30_wp, 1.0e30_wp)
                    cal%values = [cal%values, x]
                end do
            end associate
        end select
    end subroutine read_values_card

    !> CURVES file (columns 11-80): the rated curves of an evaluation alone.
    subroutine read_curves_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                       !! the card's line
        select type (st => deck)
        type is (calibration_reading_t)
            st%cal%curves = st%rd%text(i, 11)
        end select
    end subroutine read_curves_card

    !> The checks across cards, after the last: each PEAK card's channel a
    !! CHANNEL card's (its curve), at least one CASE each with its DATA
    !! (one FIT and one RATING card: the card engine), CHANNEL and PEAK cards when a case has
    !! volunteers, one value per PARAM card on the VALUES cards, each
    !! OPTIONAL name a PARAM card's.
    subroutine check_calibration_cards(st, cal, source)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards
        type(calibration_t), intent(inout) :: cal      !! the calibration: its peaks' curves set
        character(len=*), intent(in) :: source         !! the deck's name in messages
        integer :: k
        associate (rd => st%rd)
            do k = 1, size(cal%peaks)
                if (rd%failed()) exit
                cal%peaks(k)%curve = channel_number(cal, st%peak_channel(k))
                if (cal%peaks(k)%curve == 0) &
                    call rd%fail(rd%context(st%peak_line(k), 1, 'channel')//': found "'//trim(st%peak_channel(k))// &
                                 '"; expected the channel of a CHANNEL card')
            end do
            if (.not. rd%failed() .and. (size(cal%decks) == 0 .or. size(cal%data) /= size(cal%decks))) &
                call rd%fail(source//': expected at least one CASE card, each followed by its DATA card')
            if (.not. rd%failed() .and. .not. all(st%is_ref) .and. (size(cal%channels) == 0 .or. &
                                                                  size(cal%peaks) == 0)) &
                call rd%fail(source//': expected at least one CHANNEL and one PEAK card (the deck has a case of '// &
                             'volunteers, a DATA directory)')
            do k = 1, size(st%optional)
                if (rd%failed()) exit
                if (.not. any(adjustl(st%params%text(11:20)) == st%optional(k))) &
                    call rd%fail(rd%where(st%optional_line(k))//' (OPTIONAL card): found "'// &
                                 trim(st%optional(k))//'"; expected the name of a PARAM card')
            end do
            if (.not. rd%failed() .and. st%values_line > 0 .and. size(cal%values) /= param_count(st%params)) &
                call rd%fail(rd%where(st%values_line)//' (VALUES card): found '//trim(int_str(size(cal%values)))// &
                             ' values on the VALUES cards; expected one per parameter (PARAM name), '// &
                             trim(int_str(param_count(st%params))))
            if (.not. rd%failed() .and. st%values_line > 0) call check_values_in_range(st, cal%values)
        end associate
    end subroutine check_calibration_cards

    !> Each VALUES value within the range (F5, F6) of its PARAM card, the
    !! first card of its name; a card without a range is not checked.
    subroutine check_values_in_range(st, values)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards; out: a located error
        real(wp), intent(in) :: values(:)              !! the VALUES, one per parameter in PARAM order
        real(wp) :: lo, hi
        integer :: k, j, p, ios1, ios2
        p = 0
        do k = 1, size(st%params)
            if (any([(upper(adjustl(st%params(j)%text(11:20))) == upper(adjustl(st%params(k)%text(11:20))), &
                      j=1, k - 1)])) cycle
            p = p + 1
            read (st%params(k)%text(51:60), *, iostat=ios1) lo
            read (st%params(k)%text(61:70), *, iostat=ios2) hi
            if (ios1 /= 0 .or. ios2 /= 0 .or. p > size(values)) cycle
            if (hi <= lo .or. (values(p) >= lo .and. values(p) <= hi)) cycle
            call st%rd%fail(st%rd%where(st%values_line)//' (VALUES cards): value '//trim(int_str(p))//' (PARAM '// &
                            trim(adjustl(st%params(k)%text(11:20)))//') is '//trim(real_str(values(p)))// &
                            '; expected one within its range, '//trim(adjustl(st%params(k)%text(51:60)))//' to '// &
                            trim(adjustl(st%params(k)%text(61:70))))
            return
        end do
    end subroutine check_values_in_range

    !> The number of parameters of the PARAM cards: a card that repeats an
    !! earlier card's name is a further field of that parameter.
    pure integer function param_count(params) result(n)
        type(deck_line_t), intent(in) :: params(:)  !! the PARAM cards
        integer :: k, j
        n = 0
        do k = 1, size(params)
            n = n + 1
            do j = 1, k - 1
                if (upper(adjustl(params(j)%text(11:20))) /= upper(adjustl(params(k)%text(11:20)))) cycle
                n = n - 1
                exit
            end do
        end do
    end function param_count

    !> The number of the CHANNEL card of channel `name` so far (0: none).
    pure integer function channel_number(cal, name) result(n)
        type(calibration_t), intent(in) :: cal   !! the calibration so far
        character(len=*), intent(in) :: name     !! the channel
        do n = size(cal%channels), 1, -1
            if (cal%channels(n)%name == name) return
        end do
    end function channel_number

    !> The number of the PEAK card named `name` so far (0: none).
    pure integer function peak_number(cal, name) result(n)
        type(calibration_t), intent(in) :: cal   !! the calibration so far
        character(len=*), intent(in) :: name     !! the peak's name
        do n = size(cal%peaks), 1, -1
            if (cal%peaks(n)%name == name) return
        end do
    end function peak_number

    !> "stdin line 12, columns 41-80 (CHANNEL card, 'data file')".
    function columns(rd, i, c1, what) result(s)
        type(deck_reader_t), intent(in) :: rd    !! the deck
        integer, intent(in) :: i                 !! the card's line
        integer, intent(in) :: c1                !! the first column of its text
        character(len=*), intent(in) :: what     !! what the text is
        character(len=:), allocatable :: s
        s = rd%where(i)//', columns '//trim(int_str(c1))//'-80 ('//trim(rd%key(i))//' card, '''//what//''')'
    end function columns

end module hn_calibrate_deck
