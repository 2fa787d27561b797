!> The cases of a calibration deck, its cards read (hn_calibrate_deck):
!! each case bound to its deck through a sweep of the PARAM cards and its
!! data read by its kind -- volunteers (a DATA directory of their runs),
!! a reference CSV (its RATED cards), or a CSV of published peaks -- and
!! checked against its deck's channels and the rating (its window, ISO
!! 18571's least samples); the STANDING decks bound the same way.
module hn_calibrate_cases
    use hn_kinds, only: wp, zero, one, msglen
    use hn_status, only: stat_ok, stat_bad_input
    use hn_case, only: case_t, deck_line_t
    use hn_deck_state, only: real_str
    use hn_deck_reader, only: int_str
    use hn_strings, only: int_field
    use hn_sweep, only: read_sweep_lines, sweep_member_case, field_text, param_target_text
    use hn_channels, only: channel_set_t, channels_define
    use hn_rating, only: window_samples, max_lag
    use hn_volunteer_data, only: read_volunteers, read_reference_csv, read_peak_table
    use hn_iso18571, only: iso18571_rating_t, iso18571_rating, iso18571_min_samples
    use hn_calibrate_types, only: calibration_t, calibration_deck_t, reference_case_t, metric_iso18571
    use hn_calibrate_deck, only: read_calibration_cards, read_cfc_class, columns
    use hn_calibrate_scores, only: window_rows, rated_interval
    implicit none
    private

    public :: read_calibration

contains

    !> Read a calibration deck: its cards (read_calibration_cards), then
    !! each case's parameters bound to its own deck through a sweep (same
    !! checks) and its data read: every CHANNEL must be a channel of every
    !! case deck, and every volunteer file is read (bind_cases, docs/sweeps.md).
    subroutine read_calibration(path, source, cal, stat, errmsg, include_path)
        character(len=*), intent(in) :: path     !! the calibration deck's file
        character(len=*), intent(in) :: source   !! its name in messages
        type(calibration_t), intent(out) :: cal  !! the calibration
        integer, intent(out) :: stat             !! stat_ok, or stat_bad_input
        character(len=msglen), intent(out) :: errmsg !! the deck line, columns and what was expected
        character(len=*), intent(in), optional :: include_path(:)  !! directories searched for CASE decks and INCLUDE files
        type(calibration_deck_t) :: st
        call read_calibration_cards(path, source, cal, st, include_path)
        stat = st%rd%stat; errmsg = st%rd%errmsg
        if (stat /= stat_ok) return
        call bind_cases(st, cal, path, source, stat, errmsg, include_path)
    end subroutine read_calibration

    !> Each case bound to its deck through a sweep of the PARAM cards (its
    !! parameters' nominal values that deck's; an OPTIONAL one left unbound
    !! where the deck lacks its target), then its data read: a reference CSV
    !! (reference_case) or the volunteers (volunteer_case); the STANDING
    !! decks bound the same way; the parameter table cal%par, each
    !! parameter as the first case binding it binds it.
    subroutine bind_cases(st, cal, path, source, stat, errmsg, include_path)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards, all valid
        type(calibration_t), intent(inout) :: cal      !! the calibration: its sweeps and cases' data
        character(len=*), intent(in) :: path           !! the calibration deck's file
        character(len=*), intent(in) :: source         !! its name in messages
        integer, intent(out) :: stat                   !! stat_ok, or stat_bad_input
        character(len=msglen), intent(out) :: errmsg   !! the deck line, columns and what was expected
        character(len=*), intent(in), optional :: include_path(:)  !! directories searched for CASE decks and INCLUDE files
        type(deck_line_t), allocatable :: sl(:)
        type(case_t) :: cs
        type(channel_set_t) :: chs
        real(wp), allocatable :: v0(:)
        integer :: c, p, k
        stat = stat_ok; errmsg = ''
        allocate (cal%sw(size(cal%decks)), cal%vol(size(cal%decks)), cal%ref(size(cal%decks)), cal%pub(size(cal%decks)))
        do c = 1, size(cal%decks)
            sl = [line_of('TITLE     '//cal%title, source), line_of('BASE      '//trim(cal%decks(c)), source), &
                  line_of('DESIGN    LHS       '//int_field(cal%nstart)//int_field(cal%seed), source), st%params]
            call read_sweep_lines(sl, source, cal%sw(c), stat, errmsg, include_path, path, st%optional)
            if (stat /= stat_ok) return
            v0 = cal%sw(c)%params%nominal
            call sweep_member_case(cal%sw(c), v0, cs, stat, errmsg, deck_sampling=st%is_ref(c))
            if (stat /= stat_ok) return
            call channels_define(cs, chs)
            if (st%is_ref(c)) then
                call reference_case(st, cal, c, chs, cs%sample_dt, stat, errmsg)
            else if (st%is_pub(c)) then
                call published_case(st, cal, c, chs, stat, errmsg)
            else
                call volunteer_case(st, cal, c, chs, stat, errmsg)
            end if
            if (stat /= stat_ok) return
        end do
        do k = 1, size(cal%stand)
            sl = [line_of('TITLE     '//cal%title, source), line_of('BASE      '//trim(cal%stand(k)%deck), source), &
                  line_of('DESIGN    LHS       '//int_field(cal%nstart)//int_field(cal%seed), source), st%params]
            call read_sweep_lines(sl, source, cal%stand(k)%sw, stat, errmsg, include_path, path, st%optional)
            if (stat /= stat_ok) return
            call sweep_member_case(cal%stand(k)%sw, cal%stand(k)%sw%params%nominal, cs, stat, errmsg)
            if (stat /= stat_ok) return
        end do
        cal%par = cal%sw(1)%params
        do p = 1, size(cal%par)
            c = findloc([(cal%sw(k)%params(p)%bound, k=1, size(cal%sw))], .true., dim=1)
            if (c == 0) then
                k = findloc(st%optional, cal%par(p)%name, dim=1)
                stat = stat_bad_input
                errmsg = st%rd%where(st%optional_line(k))//' (OPTIONAL card): PARAM '//trim(cal%par(p)%name)// &
                         ' is bound in no case: no case deck has its '//trim(param_target_text(cal%par(p)))// &
                         '; expected at least one'
                return
            end if
            cal%par(p) = cal%sw(c)%params(p)
        end do
    end subroutine bind_cases

    !> The volunteers of case c: every CHANNEL a channel of its deck, their
    !! runs read from its DATA directory, the RATING window holding enough
    !! of their times, their mean curves ones the metric can rate.
    subroutine volunteer_case(st, cal, c, chs, stat, errmsg)
        type(calibration_deck_t), intent(in) :: st     !! the deck and its cards, all valid
        type(calibration_t), intent(inout) :: cal      !! the calibration: cal%vol(c) read
        integer, intent(in) :: c                       !! the case
        type(channel_set_t), intent(in) :: chs         !! the channels of its deck
        integer, intent(out) :: stat                   !! stat_ok, or stat_bad_input
        character(len=msglen), intent(inout) :: errmsg !! the deck line, columns and what was expected
        integer :: k, bad_channel, bad_peak, nwin, nmin, i1, i2
        associate (rd => st%rd)
            call rated_channels_check(st, cal, c, chs, stat, errmsg)
            if (stat /= stat_ok) return
            call read_volunteers(trim(cal%data(c)), cal%channels, cal%cfc, cal%peaks, cal%vol(c), stat, errmsg, &
                                 bad_channel, bad_peak)
            if (stat /= stat_ok) then
                if (bad_channel > 0) then
                    errmsg = columns(rd, st%channel_line(bad_channel), 41, 'data file')//', in the directory of '// &
                             'the DATA card at '//rd%where(st%data_line(c))//': '//errmsg
                else if (bad_peak > 0) then
                    errmsg = rd%context(st%peak_line(bad_peak), 3, 'window start')//': '//errmsg
                end if
                return
            end if
            call window_samples(cal%vol(c)%t, cal%window, nwin, nmin)
            if (nwin < nmin) then
                stat = stat_bad_input
                errmsg = rd%context(st%rating_line, 2, 'window end')//': the window '// &
                         trim(rd%raw(st%rating_line, 1))//' to '//trim(rd%raw(st%rating_line, 2))//' ms holds '// &
                         trim(int_str(nwin))//' times of the volunteer data of the DATA card at '// &
                         rd%where(st%data_line(c))//'; expected at least '//trim(int_str(nmin))// &
                         ' (the rating''s largest lag, '//trim(field_text(max_lag))//' ms, in samples, plus 2)'
                return
            end if
            if (cal%metric == metric_iso18571) then
                call window_rows(cal%vol(c)%t, cal%window, i1, i2)
                do k = 1, size(cal%channels)
                    call iso_check(st, cal%vol(c)%mean(i1:i2, k), (cal%vol(c)%t(2) - cal%vol(c)%t(1))*1.0e-3_wp, &
                                   'the volunteers'' mean of '// &
                                   trim(cal%channels(k)%name)//' on the RATING window', st%data_line(c), stat, errmsg)
                    if (stat /= stat_ok) return
                end do
            end if
        end associate
    end subroutine volunteer_case

    !> Every CHANNEL card's channel is one of case c's channels.
    subroutine rated_channels_check(st, cal, c, chs, stat, errmsg)
        type(calibration_deck_t), intent(in) :: st     !! the deck and its cards, all valid
        type(calibration_t), intent(in) :: cal         !! the calibration
        integer, intent(in) :: c                       !! the case
        type(channel_set_t), intent(in) :: chs         !! the channels of its deck
        integer, intent(out) :: stat                   !! stat_ok, or stat_bad_input
        character(len=msglen), intent(inout) :: errmsg !! the CHANNEL card's line and columns, and what was expected
        integer :: k
        stat = stat_ok
        do k = 1, size(cal%channels)
            if (findloc(chs%name, cal%channels(k)%name, dim=1) == 0) then
                stat = stat_bad_input
                errmsg = st%rd%context(st%channel_line(k), 1, 'channel')//': found "'// &
                         trim(cal%channels(k)%name)//'"; expected a channel of the case deck '// &
                         trim(cal%decks(c))//' (docs/output-format.md)'
                return
            end if
        end do
    end subroutine rated_channels_check

    !> The published peaks of case c (its DATA a CSV of peaks: peak, mean,
    !! sd[, time_mean, time_sd], each row a PEAK card's name): every
    !! CHANNEL a channel of its deck, the table read.
    subroutine published_case(st, cal, c, chs, stat, errmsg)
        type(calibration_deck_t), intent(in) :: st     !! the deck and its cards, all valid
        type(calibration_t), intent(inout) :: cal      !! the calibration: cal%pub(c) read
        integer, intent(in) :: c                       !! the case
        type(channel_set_t), intent(in) :: chs         !! the channels of its deck
        integer, intent(out) :: stat                   !! stat_ok, or stat_bad_input
        character(len=msglen), intent(inout) :: errmsg !! the deck line, the file's line and what was expected
        call rated_channels_check(st, cal, c, chs, stat, errmsg)
        if (stat /= stat_ok) return
        call read_peak_table(trim(cal%data(c)), cal%peaks%name, cal%pub(c), stat, errmsg)
        if (stat /= stat_ok) errmsg = st%rd%where(st%data_line(c))//' (DATA card): '//errmsg
    end subroutine published_case

    !> The rated channels of reference case c: its CSV read, its RATED
    !! cards (or every column under its own name) checked against the
    !! CSV and the case deck's channels (a CFC class on samples at least
    !! ten to its period: rated_columns), each curve one the metric can rate.
    subroutine reference_case(st, cal, c, chs, sample_dt, stat, errmsg)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards, all valid
        type(calibration_t), intent(inout) :: cal      !! the calibration: cal%ref(c) read
        integer, intent(in) :: c                       !! the case
        type(channel_set_t), intent(in) :: chs         !! the channels of its deck
        real(wp), intent(in) :: sample_dt              !! its runs' sampling interval (the deck's OUTPUT) [s]
        integer, intent(out) :: stat                   !! stat_ok, or stat_bad_input
        character(len=msglen), intent(inout) :: errmsg !! the deck line, columns and what was expected
        integer :: m, n, nwin, nmin
        associate (rf => cal%ref(c))
            rf%on = .true.
            call read_reference_csv(trim(cal%data(c)), rf%data, stat, errmsg)
            if (stat /= stat_ok) then
                errmsg = st%rd%where(st%data_line(c))//' (DATA card): '//errmsg
                return
            end if
            n = count(st%rated_case == c)
            if (n == 0) n = size(rf%data%name)
            allocate (rf%column(n), rf%col(n), rf%channel(n), rf%scale(n), rf%minus(n), rf%from_start(n), &
                      rf%as_samples(n), rf%cfc(n))
            rf%scale = one; rf%minus = ''; rf%from_start = .false.; rf%as_samples = .false.; rf%cfc = zero
            if (count(st%rated_case == c) == 0) then
                rf%column = rf%data%name
                rf%channel = rf%data%name
                do m = 1, n
                    rf%col(m) = m
                    if (findloc(chs%name, rf%channel(m), dim=1) == 0) then
                        stat = stat_bad_input
                        errmsg = st%rd%where(st%data_line(c))//' (DATA card): column "'//trim(rf%channel(m))// &
                                 '" of '//trim(cal%data(c))//' is no channel of the case deck '// &
                                 trim(cal%decks(c))//'; expected RATED cards naming the model channel of '// &
                                 'each column, or columns named as channels (docs/output-format.md)'
                        return
                    end if
                end do
            else
                call rated_columns(st, c, cal%data(c), cal%decks(c), chs, sample_dt, rf, stat, errmsg)
                if (stat /= stat_ok) return
            end if
            do m = 1, n
                associate (d => rf%data, k => rf%col(m))
                    if (cal%metric == metric_iso18571) then
                        call iso_check(st, d%mean(d%first(k):d%last(k), k), rated_interval(rf, m), &
                                       'reference "'//trim(d%name(k))// &
                                       '"', st%data_line(c), stat, errmsg)
                    else
                        call window_samples(d%t(d%first(k):d%last(k)), [d%t(d%first(k)), d%t(d%last(k))], &
                                            nwin, nmin)
                        if (nwin < nmin) then
                            stat = stat_bad_input
                            errmsg = st%rd%where(st%data_line(c))//' (DATA card): reference "'//trim(d%name(k))// &
                                     '" of '//trim(cal%data(c))//' holds '//trim(int_str(nwin))// &
                                     ' times; expected at least '//trim(int_str(nmin))// &
                                     ' for the CORA-style rating (its largest lag, 30 ms, in samples, plus 2)'
                        end if
                    end if
                end associate
                if (stat /= stat_ok) return
            end do
        end associate
    end subroutine reference_case

    !> The RATED cards of reference case c, in their order: CSV column,
    !! model channel, [scale], [subtracted channel], [START], [SAMPLES], [CFC class], each column
    !! one of the CSV's and rated once, each channel one of the case deck's,
    !! a CFC class on runs sampled at 10 times the class or more.
    subroutine rated_columns(st, c, data, deck, chs, sample_dt, rf, stat, errmsg)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards, all valid
        integer, intent(in) :: c                       !! the case
        character(len=*), intent(in) :: data           !! its reference CSV
        character(len=*), intent(in) :: deck           !! its case deck
        type(channel_set_t), intent(in) :: chs         !! the channels of its deck
        real(wp), intent(in) :: sample_dt              !! its runs' sampling interval [s]
        type(reference_case_t), intent(inout) :: rf    !! its reference, the CSV read: the rated channels set
        integer, intent(out) :: stat                   !! stat_ok, or stat_bad_input
        character(len=msglen), intent(inout) :: errmsg !! the deck line, columns and what was expected
        integer :: m, r, l, col
        character(len=10) :: column, chan, minus, fs, smp
        real(wp) :: sc, cfc
        stat = stat_ok
        associate (rd => st%rd)
            m = 0
            do r = 1, size(st%rated_line)
                if (st%rated_case(r) /= c) cycle
                l = st%rated_line(r)
                m = m + 1
                call rd%name(l, 1, 'CSV column', column)
                call rd%name(l, 2, 'channel', chan)
                call rd%real(l, 3, 'scale', '-', sc, -1.0e6_wp, 1.0e6_wp, default=one)
                minus = ''
                if (.not. rd%is_blank(l, 4)) call rd%name(l, 4, 'subtracted channel', minus)
                fs = ''
                if (.not. rd%failed() .and. .not. rd%is_blank(l, 5)) &
                    call rd%choice(l, 5, 'origin', [character(len=10) :: 'START'], fs)
                smp = ''
                if (.not. rd%failed() .and. .not. rd%is_blank(l, 6)) &
                    call rd%choice(l, 6, 'sampling', [character(len=10) :: 'SAMPLES'], smp)
                cfc = zero
                if (.not. rd%failed() .and. .not. rd%is_blank(l, 7)) call read_cfc_class(rd, l, 7, cfc)
                if (.not. rd%failed() .and. cfc*sample_dt > 0.1_wp*(one + 1.0e-9_wp)) &
                    call rd%fail(rd%context(l, 7, 'CFC class')//': found '//trim(rd%raw(l, 7))//' on runs of '// &
                                 trim(deck)//' sampled every '//trim(real_str(1.0e3_wp*sample_dt))//' ms (its OUTPUT '// &
                                 'card); expected samples at least ten times the class, every '// &
                                 trim(real_str(1.0e2_wp/cfc))//' ms or less')
                if (rd%failed()) then
                    stat = rd%stat; errmsg = rd%errmsg; return
                end if
                col = findloc(rf%data%name, column, dim=1)
                if (col == 0) then
                    stat = stat_bad_input
                    errmsg = rd%context(l, 1, 'CSV column')//': found "'//trim(column)//'"; expected a '// &
                             'channel column of '//trim(data)
                    return
                end if
                if (any(rf%column(1:m - 1) == column)) then
                    stat = stat_bad_input
                    errmsg = rd%context(l, 1, 'CSV column')//': found "'//trim(column)//'" again; '// &
                             'expected one RATED card per column'
                    return
                end if
                if (findloc(chs%name, chan, dim=1) == 0) then
                    stat = stat_bad_input
                    errmsg = rd%context(l, 2, 'channel')//': found "'//trim(chan)//'"; expected a '// &
                             'channel of the case deck '//trim(deck)//' (docs/output-format.md)'
                    return
                end if
                if (len_trim(minus) > 0 .and. findloc(chs%name, minus, dim=1) == 0) then
                    stat = stat_bad_input
                    errmsg = rd%context(l, 4, 'subtracted channel')//': found "'//trim(minus)// &
                             '"; expected a channel of the case deck '//trim(deck)
                    return
                end if
                rf%column(m) = column; rf%col(m) = col; rf%channel(m) = chan; rf%scale(m) = sc
                rf%minus(m) = minus; rf%from_start(m) = fs == 'START'; rf%as_samples(m) = smp == 'SAMPLES'
                rf%cfc(m) = cfc
            end do
        end associate
    end subroutine rated_columns

    !> stat_bad_input with the DATA card's location when ISO 18571 cannot
    !! rate against curve r (samples dt apart): too short, constant.
    subroutine iso_check(st, r, dt, what, line, stat, errmsg)
        type(calibration_deck_t), intent(in) :: st     !! the deck (the DATA card's location)
        real(wp), intent(in) :: r(:)                   !! the curve
        real(wp), intent(in) :: dt                     !! its sampling interval as the rating takes it [s]
        character(len=*), intent(in) :: what           !! what the curve is, in the message
        integer, intent(in) :: line                    !! the DATA card's line
        integer, intent(out) :: stat                   !! stat_ok, or the rating's error
        character(len=msglen), intent(inout) :: errmsg !! on an error: the DATA card, the curve and why
        type(iso18571_rating_t) :: rt
        character(len=msglen) :: m
        call iso18571_rating(r, r, dt, rt, stat, m)
        if (stat /= stat_ok) errmsg = st%rd%where(line)//' (DATA card): '//what//': '//trim(m)// &
                                      ' (RATING F5 ISO18571 needs at least '// &
                                      trim(int_str(iso18571_min_samples))//' samples at 10 kHz)'
    end subroutine iso_check

    !> A card image of a case's sweep, made by the calibration (line 0).
    pure function line_of(text, source) result(l)
        character(len=*), intent(in) :: text     !! the card
        character(len=*), intent(in) :: source   !! the calibration deck's name in messages
        type(deck_line_t) :: l
        l%text = text
        l%source = source
        l%line = 0
    end function line_of

end module hn_calibrate_cases
