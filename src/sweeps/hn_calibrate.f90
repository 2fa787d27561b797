!> Calibration as code: fit named deck parameters (the PARAM cards of the
!! sweep deck: FAMILY scale factors, BODY scales, FIELDn values), within
!! their bounds, to the volunteers of one or more cases, by minimising
!!
!!   J = (1 - R) + w P + wt T,
!!
!! R the mean CORA-style rating (hn_rating) of the rated channels (the
!! deck's CHANNEL cards) over the cases, P the mean over the cases' peaks
!! (PEAK cards) of max(0, |z| - (1 - m)), z the peak's distance from the
!! volunteers' mean in SDs and m a margin inside the 1 SD band, T the mean
!! over the same peaks of max(0, |dt|/tol - (1 - m)), dt the peak time's
!! distance from the volunteers' mean time and tol the peak-time tolerance
!! of the RATING card (the same margin keeps the times off its edge); w
!! (default 0.02), wt (default 0) and m (default 0) are fields 5, 6 and 7
!! of the FIT card; subject to the model standing at rest: a parameter set
!! whose start state (posture held, the bracing activation) has an
!! eigenvalue with real part above -1 1/s in any case (hn_rest_modes) is
!! not run and gets J = 2 + 0.1 s (lmax + 1); with a PASSIVE card, nor is a
!! set whose neck stands without its muscles (largest real part at rest,
!! muscles off, below the card's limit, default 0: the osteoligamentous
!! column buckles under far less than the head's weight), which gets
!! J = 2 + 0.1 s (limit - lp). The study itself (the volunteer files, the
!! channels they are compared with, the rating window, the filter, the
!! peaks and their windows) is the deck's RATING, CHANNEL and PEAK cards;
!! nothing of it is compiled in.
!! Optimizer (hn_optimize): a Latin hypercube of starting points (seeded)
!! and Nelder-Mead from the best of them, restarted about its best point
!! while a restart gains more than 1e-4, in the unit cube of the parameter
!! ranges (LOG ranges in logarithms), points clamped to the bounds.
!! Deterministic: the same deck gives the same fit on every machine.
!! Member runs are those of the sweep (sweep_member_case, run_state_t).
module hn_calibrate
    use hn_kinds, only: wp, zero, one, msglen
    use hn_status, only: stat_ok, stat_bad_input
    use hn_case, only: case_t, deck_line_t, path_len
    use hn_deck_reader, only: deck_reader_t, read_card_images, int_str
    use hn_sweep, only: sweep_t, sweep_param_t, read_sweep_lines, sweep_member_case, sweep_design, spread_value, &
                        field_text, par_field
    use hn_run, only: run_state_t, run_result_t, exit_ok
    use hn_channels, only: channel_set_t, channels_define
    use hn_filters, only: cfc_filter
    use hn_tables, only: resample
    use hn_optimize, only: restarted_nelder_mead
    use hn_rating, only: peak_t, corridor_t, score_t, score_curves, window_samples, max_lag
    use hn_volunteer_data, only: data_channel_t, read_volunteers
    use hn_rest_modes, only: rest_mode_t, rest_modes
    use hn_model, only: fam_muscles
    implicit none
    private

    public :: calibration_t, read_calibration, evaluate, calibrate, member_histories

    real(wp), parameter :: failed_objective = 10.0_wp        !! J of a parameter set whose run fails
    real(wp), parameter :: rest_margin = -1.0_wp             !! largest real part allowed at rest [1/s]
    real(wp), parameter :: unstable_objective = 2.0_wp       !! J of a set unstable at rest, at the margin
    real(wp), parameter :: unstable_slope = 0.1_wp           !! its growth per 1/s beyond the margin [s]
    integer, parameter :: peak_name_len = 16                 !! longest peak name (PEAK card, columns 51-80)

    !> A calibration: its cases (deck, volunteers, the sweep that binds the
    !! parameters to that deck), the study (rated channels, peaks, rating
    !! window, filter) and the optimizer's settings.
    type :: calibration_t
        character(len=80) :: title = ''
        character(len=path_len), allocatable :: decks(:), data(:)
        type(sweep_t), allocatable :: sw(:)
        type(corridor_t), allocatable :: vol(:)     !! the volunteers of each case
        type(data_channel_t), allocatable :: channels(:)   !! CHANNEL cards: the rated channels
        type(peak_t), allocatable :: peaks(:)       !! PEAK cards (curve: a channel number)
        real(wp) :: window(2) = zero                !! RATING F1, F2: the rated times [ms]
        real(wp) :: cfc = zero                      !! RATING F3: CFC class of model and volunteer channels [Hz]
        real(wp) :: time_tolerance = zero           !! RATING F4: peak-time tolerance of the goal [ms]
        integer :: max_evals = 200, nstart = 8, seed = 1
        real(wp) :: peak_weight = 0.02_wp           !! w of the objective (FIT F5)
        real(wp) :: time_weight = zero              !! wt of the objective (FIT F6)
        real(wp) :: peak_margin = zero              !! m of the objective: P counts |z| above 1 - m (FIT F7)
        logical :: passive = .false.                !! PASSIVE card: the neck without its muscles must not stand
        real(wp) :: passive_limit = zero            !! its largest real part at rest must be above this (PASSIVE F1) [1/s]
        real(wp), allocatable :: values(:)          !! VALUES cards: the point scored when max_evals = 0
    end type calibration_t

contains

    !> Read a calibration deck: TITLE; CASE path (columns 11-80) followed by
    !! DATA directory of that case's volunteers; FIT NELDER max-evaluations
    !! starting-points seed [peak-weight [peak-time-weight [peak-margin]]];
    !! RATING window-start window-end CFC-class peak-time-tolerance; CHANNEL
    !! cards (channel, VALUE or RATE, [DEG-RAD], the file in columns
    !! 41-80); PEAK cards (channel, MIN or MAX, window start and end, the
    !! name in columns 51-80); PARAM cards as in a sweep deck; optional
    !! PASSIVE [limit] (a set whose neck stands without its muscles is not
    !! run); optional VALUES cards (up to 7 values each, in PARAM order), the
    !! point scored when max-evaluations is 0 (default: the decks' own
    !! values). Each case's parameters are bound to its own deck through a
    !! sweep (same checks); every CHANNEL must be a channel of every case
    !! deck, and every volunteer file is read (docs/sweeps.md).
    subroutine read_calibration(path, source, cal, stat, errmsg, include_path)
        character(len=*), intent(in) :: path     !! the calibration deck's file
        character(len=*), intent(in) :: source   !! its name in messages
        type(calibration_t), intent(out) :: cal  !! the calibration
        integer, intent(out) :: stat             !! stat_ok, or stat_bad_input
        character(len=msglen), intent(out) :: errmsg !! the deck line, columns and what was expected
        character(len=*), intent(in), optional :: include_path(:)  !! directories searched for CASE decks and INCLUDE files
        type(deck_reader_t) :: rd
        type(deck_line_t), allocatable :: params(:), sl(:)
        type(data_channel_t) :: dc
        type(peak_t) :: pk
        type(case_t) :: cs
        type(channel_set_t) :: chs
        character(len=10) :: s, opt
        character(len=:), allocatable :: ctext, found
        character(len=msglen) :: msg
        character(len=10), allocatable :: peak_channel(:)
        integer, allocatable :: channel_line(:), peak_line(:), data_line(:)
        integer :: i, c, k, nfit, f, rating_line, cfc, bad_peak, bad_channel, nwin, nmin
        real(wp) :: x
        real(wp), allocatable :: v0(:)
        rd%top = source
        if (present(include_path)) rd%search = include_path
        call read_card_images(rd, path, source, 0)
        allocate (cal%decks(0), cal%data(0), params(0), cal%values(0), cal%channels(0), cal%peaks(0))
        allocate (channel_line(0), peak_line(0), data_line(0), peak_channel(0))
        nfit = 0; rating_line = 0
        do i = 1, rd%nlines
            if (rd%failed()) exit
            select case (rd%key(i))
            case ('TITLE'); cal%title = adjustl(rd%lines(i)%text(11:80))
            case ('CASE'); cal%decks = [character(len=path_len) :: cal%decks, adjustl(rd%lines(i)%text(11:80))]
            case ('DATA')
                if (size(cal%data) /= size(cal%decks) - 1) then
                    call rd%fail(rd%where(i)//' (DATA card): expected one DATA card after each CASE card')
                    exit
                end if
                ! found as an INCLUDE file is: next to the calibration deck, in the
                ! working directory, then on the include path (-I, HHNECK_PATH)
                call rd%find_file(trim(adjustl(rd%lines(i)%text(11:80))), rd%lines(i)%source, found, msg, &
                                  directory=.true.)
                if (len(found) == 0) then
                    call rd%fail(rd%where(i)//' (DATA card): '//trim(msg))
                    exit
                end if
                cal%data = [character(len=path_len) :: cal%data, found]
                data_line = [data_line, i]
            case ('FIT')
                nfit = nfit + 1
                call rd%name(i, 1, 'optimizer', s)
                if (s /= 'NELDER' .and. .not. rd%failed()) call rd%fail(rd%context(i, 1, 'optimizer')// &
                                                                       ': found "'//trim(s)//'"; expected NELDER')
                call rd%int(i, 2, 'maximum evaluations', cal%max_evals, 0, 100000)
                call rd%int(i, 3, 'starting points', cal%nstart, 2, 10000)
                call rd%int(i, 4, 'seed', cal%seed, 1, 2147483646)
                call rd%real(i, 5, 'peak weight', '-', cal%peak_weight, zero, 1.0e3_wp, default=0.02_wp)
                call rd%real(i, 6, 'peak-time weight', '-', cal%time_weight, zero, 1.0e3_wp, default=zero)
                call rd%real(i, 7, 'peak margin', 'SD', cal%peak_margin, zero, 0.9_wp, default=zero)
            case ('RATING')
                if (rating_line > 0) then
                    call rd%fail(rd%where(i)//', columns 1-8 (RATING card): found a second RATING card; '// &
                                 'expected one (the RATING card at '//rd%where(rating_line)//' has it)')
                    exit
                end if
                rating_line = i
                call rd%real(i, 1, 'window start', 'ms', cal%window(1), zero, 1.0e6_wp)
                call rd%real(i, 2, 'window end', 'ms', cal%window(2), zero, 1.0e6_wp)
                if (.not. rd%failed() .and. .not. cal%window(2) > cal%window(1)) &
                    call rd%fail(rd%context(i, 2, 'window end')//': found '//trim(rd%raw(i, 2))// &
                                 ' ms; expected a time after the window start '//trim(rd%raw(i, 1))//' ms')
                call rd%int(i, 3, 'CFC class', cfc, 1, 100000)
                if (.not. rd%failed() .and. all(cfc /= [60, 180, 600, 1000])) &
                    call rd%fail(rd%context(i, 3, 'CFC class')//': found '//trim(rd%raw(i, 3))// &
                                 '; expected 60, 180, 600 or 1000 (SAE J211/1)')
                cal%cfc = real(cfc, wp)
                call rd%real(i, 4, 'peak-time tolerance', 'ms', cal%time_tolerance, 1.0e-3_wp, 1.0e6_wp)
            case ('CHANNEL')
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
                    call rd%fail(columns(i, 41, 'data file')//': found a blank; expected the name of the file '// &
                                 'of the channel''s runs in each DATA directory')
                if (rd%failed()) exit
                k = channel_number(dc%name)
                if (k > 0) then
                    call rd%fail(rd%context(i, 1, 'channel')//': found "'//trim(dc%name)//'" again; expected '// &
                                 'one CHANNEL card per channel (the CHANNEL card at '// &
                                 rd%where(channel_line(k))//' has it)')
                    exit
                end if
                cal%channels = [cal%channels, dc]
                channel_line = [channel_line, i]
            case ('PEAK')
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
                    call rd%fail(columns(i, 51, 'peak name')//': found "'//ctext//'"; expected a name of 1 to '// &
                                 trim(int_str(peak_name_len))//' characters')
                if (rd%failed()) exit
                pk%name = ctext
                k = peak_number(pk%name)
                if (k > 0) then
                    call rd%fail(columns(i, 51, 'peak name')//': found "'//trim(pk%name)//'" again; expected '// &
                                 'one PEAK card per name (the PEAK card at '//rd%where(peak_line(k))//' has it)')
                    exit
                end if
                cal%peaks = [cal%peaks, pk]
                peak_line = [peak_line, i]
                peak_channel = [character(len=10) :: peak_channel, s]
            case ('PARAM'); params = [params, rd%lines(i)]
            case ('PASSIVE')
                cal%passive = .true.
                call rd%real(i, 1, 'largest real part at rest without muscles', '1/s', cal%passive_limit, &
                             -100.0_wp, 100.0_wp, default=zero)
            case ('VALUES')
                do f = 1, 7
                    if (rd%is_blank(i, f)) cycle
                    call rd%real(i, f, 'parameter value', '-', x, -1.0e30_wp, 1.0e30_wp)
                    cal%values = [cal%values, x]
                end do
            case ('END'); exit
            case default
                call rd%fail(rd%where(i)//', columns 1-8: found "'//trim(rd%key(i))// &
                             '"; expected TITLE, CASE, DATA, FIT, RATING, CHANNEL, PEAK, PARAM, PASSIVE, VALUES or END')
            end select
        end do
        ! a PEAK card names a CHANNEL card's channel (before or after it)
        do k = 1, size(cal%peaks)
            if (rd%failed()) exit
            cal%peaks(k)%curve = channel_number(peak_channel(k))
            if (cal%peaks(k)%curve == 0) &
                call rd%fail(rd%context(peak_line(k), 1, 'channel')//': found "'//trim(peak_channel(k))// &
                             '"; expected the channel of a CHANNEL card')
        end do
        if (.not. rd%failed() .and. (size(cal%decks) == 0 .or. size(cal%data) /= size(cal%decks) .or. nfit /= 1 &
                                     .or. rating_line == 0 .or. size(cal%channels) == 0 .or. size(cal%peaks) == 0)) &
            call rd%fail(source//': expected at least one CASE card, each followed by its DATA card, one FIT card, '// &
                         'one RATING card, and at least one CHANNEL and one PEAK card')
        stat = rd%stat; errmsg = rd%errmsg
        if (stat /= stat_ok) return
        allocate (cal%sw(size(cal%decks)), cal%vol(size(cal%decks)))
        do c = 1, size(cal%decks)
            sl = [line_of('TITLE     '//cal%title), line_of('BASE      '//trim(cal%decks(c))), &
                  line_of('DESIGN    LHS       '//int_field(cal%nstart)//int_field(cal%seed)), params]
            if (present(include_path)) then
                call read_sweep_lines(sl, source, cal%sw(c), stat, errmsg, include_path, path)
            else
                call read_sweep_lines(sl, source, cal%sw(c), stat, errmsg, path=path)
            end if
            if (stat /= stat_ok) return
            ! every rated channel is one of the case's channels
            v0 = cal%sw(c)%params%nominal
            call sweep_member_case(cal%sw(c), v0, cs, stat, errmsg)
            if (stat /= stat_ok) return
            call channels_define(cs, chs)
            do k = 1, size(cal%channels)
                if (findloc(chs%name, cal%channels(k)%name, dim=1) == 0) then
                    stat = stat_bad_input
                    errmsg = rd%context(channel_line(k), 1, 'channel')//': found "'//trim(cal%channels(k)%name)// &
                             '"; expected a channel of the case deck '//trim(cal%decks(c))//' (docs/output-format.md)'
                    return
                end if
            end do
            call read_volunteers(trim(cal%data(c)), cal%channels, cal%cfc, cal%peaks, cal%vol(c), stat, errmsg, &
                                 bad_channel, bad_peak)
            if (stat /= stat_ok) then
                if (bad_channel > 0) then
                    errmsg = columns(channel_line(bad_channel), 41, 'data file')//', in the directory of the DATA '// &
                             'card at '//rd%where(data_line(c))//': '//errmsg
                else if (bad_peak > 0) then
                    errmsg = rd%context(peak_line(bad_peak), 3, 'window start')//': '//errmsg
                end if
                return
            end if
            call window_samples(cal%vol(c)%t, cal%window, nwin, nmin)
            if (nwin < nmin) then
                stat = stat_bad_input
                errmsg = rd%context(rating_line, 2, 'window end')//': the window '//trim(rd%raw(rating_line, 1))// &
                         ' to '//trim(rd%raw(rating_line, 2))//' ms holds '//trim(int_str(nwin))// &
                         ' times of the volunteer data of the DATA card at '//rd%where(data_line(c))// &
                         '; expected at least '//trim(int_str(nmin))//' (the rating''s largest lag, '// &
                         trim(field_text(max_lag))//' ms, in samples, plus 2)'
                return
            end if
        end do
    contains
        function line_of(text) result(l)
            character(len=*), intent(in) :: text
            type(deck_line_t) :: l
            l%text = text
            l%source = source
            l%line = 0
        end function line_of
        function int_field(n) result(f)
            integer, intent(in) :: n
            character(len=10) :: f
            write (f, '(i0)') n
        end function int_field
        !> The number of the CHANNEL card of channel `name` so far (0: none).
        integer function channel_number(name) result(n)
            character(len=*), intent(in) :: name
            do n = size(cal%channels), 1, -1
                if (cal%channels(n)%name == name) return
            end do
        end function channel_number
        !> The number of the PEAK card named `name` so far (0: none).
        integer function peak_number(name) result(n)
            character(len=*), intent(in) :: name
            do n = size(cal%peaks), 1, -1
                if (cal%peaks(n)%name == name) return
            end do
        end function peak_number
        !> "stdin line 12, columns 41-80 (CHANNEL card, 'data file')".
        function columns(i, c1, what) result(s)
            integer, intent(in) :: i, c1
            character(len=*), intent(in) :: what
            character(len=:), allocatable :: s
            s = rd%where(i)//', columns '//trim(int_str(c1))//'-80 ('//trim(rd%key(i))//' card, '''//what//''')'
        end function columns
    end subroutine read_calibration

    !> Largest real part of the eigenvalues at rest (hn_rest_modes: the
    !! start state of every case, posture held as the case holds it) over
    !! the cases at parameter values v [1/s], with the muscles (lmax) and,
    !! for a PASSIVE card, without them (lp; huge without the card); each
    !! case is built once for both. Huge when a case cannot be built or
    !! analysed.
    subroutine rest_growth(cal, v, lmax, lp)
        type(calibration_t), intent(in) :: cal       !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp), intent(out) :: lmax                !! with the muscles [1/s]
        real(wp), intent(out) :: lp                  !! without them [1/s]
        type(case_t) :: cs
        type(rest_mode_t), allocatable :: modes(:)
        integer :: c, stat
        character(len=msglen) :: msg
        lmax = -huge(one)
        lp = merge(-huge(one), huge(one), cal%passive)
        do c = 1, size(cal%sw)
            call sweep_member_case(cal%sw(c), v, cs, stat, msg)
            if (stat == stat_ok) call rest_modes(cs%model, cs%t_start, cs%x0, cs%xd0, cs%hold_posture, modes, stat, msg)
            if (stat /= stat_ok) then
                lmax = huge(one); return
            end if
            if (size(modes) > 0) lmax = max(lmax, modes(1)%re)
            if (.not. cal%passive) cycle
            cs%model%family_on(fam_muscles) = .false.
            call rest_modes(cs%model, cs%t_start, cs%x0, cs%xd0, cs%hold_posture, modes, stat, msg)
            if (stat /= stat_ok) then
                lp = huge(one)
            else if (size(modes) > 0 .and. lp < huge(one)) then
                lp = max(lp, modes(1)%re)
            end if
        end do
    end subroutine rest_growth

    !> Objective J and the scores of every case for parameter values v. A
    !! parameter set whose model is not stable at rest with the margin
    !! (largest real part above rest_margin in any case: a braced neck
    !! stands) is not run: J = 2 + 0.1 s (lmax - rest_margin), worse than
    !! any stable set whose w P + wt T stays below 1, and decreasing
    !! towards stability. With a PASSIVE card, nor is a set whose neck
    !! stands without its muscles (largest real part at rest below the
    !! card's limit): J = 2 + 0.1 s (limit - lp).
    subroutine evaluate(cal, v, j, sc, ok, growth, passive_growth)
        type(calibration_t), intent(in) :: cal       !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp), intent(out) :: j                   !! the objective
        type(score_t), intent(out) :: sc(:)          !! (ncase) ratings and peaks of each case
        logical, intent(out) :: ok                   !! every run complete
        real(wp), intent(out), optional :: growth    !! largest real part at rest over the cases [1/s]
        real(wp), intent(out), optional :: passive_growth !! the same without the muscles (PASSIVE card) [1/s]
        real(wp), allocatable :: y(:, :, :)
        real(wp) :: rsum, psum, tsum, lmax, lp
        integer :: c
        call rest_growth(cal, v, lmax, lp)
        if (present(growth)) growth = lmax
        if (present(passive_growth)) passive_growth = huge(one)
        if (lmax > rest_margin) then
            ok = .false.
            j = rest_penalty(lmax - rest_margin)
            return
        end if
        if (cal%passive) then
            if (present(passive_growth)) passive_growth = lp
            if (lp < cal%passive_limit) then
                ok = .false.
                j = rest_penalty(cal%passive_limit - lp)
                return
            end if
        end if
        allocate (y(maxval([(size(cal%vol(c)%t), c=1, size(cal%vol))]), size(cal%channels), size(cal%sw)))
        call member_histories(cal, v, y, ok)
        j = failed_objective
        if (.not. ok) return
        rsum = zero; psum = zero; tsum = zero
        do c = 1, size(cal%sw)
            call score_curves(cal%vol(c), y(1:size(cal%vol(c)%t), :, c), cal%window, cal%peaks, sc(c))
            rsum = rsum + sum(sc(c)%rating)/size(cal%channels)
            psum = psum + sum(max(zero, abs(sc(c)%z) - (one - cal%peak_margin)))/size(cal%peaks)
            tsum = tsum + sum(max(zero, abs(sc(c)%time - cal%vol(c)%time_mean)/cal%time_tolerance - &
                                  (one - cal%peak_margin)))/size(cal%peaks)
        end do
        j = (one - rsum/size(cal%sw)) + (cal%peak_weight*psum + cal%time_weight*tsum)/size(cal%sw)
    end subroutine evaluate

    !> J of a parameter set that fails a check at rest by `excess` [1/s]:
    !! 2 + 0.1 s excess, worse than any set that passes, and decreasing
    !! towards the check's limit.
    pure real(wp) function rest_penalty(excess) result(j)
        real(wp), intent(in) :: excess
        j = min(failed_objective, unstable_objective + unstable_slope*excess)
    end function rest_penalty

    !> Position of value x in the unit range of parameter p (inverse of spread_value).
    pure real(wp) function unit_of(p, x) result(u)
        type(sweep_param_t), intent(in) :: p
        real(wp), intent(in) :: x
        if (p%log_spacing) then
            u = (log(x) - log(p%low))/(log(p%high) - log(p%low))
        else
            u = (x - p%low)/(p%high - p%low)
        end if
        u = min(one, max(zero, u))
    end function unit_of

    !> Run the calibration: the LHS starting points, then Nelder-Mead from
    !! the best, restarted about its best point while a restart gains more
    !! than 1e-4 and evaluations are left; the history and the result on
    !! unit lu.
    subroutine calibrate(cal, lu, vbest, jbest, nevals)
        type(calibration_t), intent(in) :: cal   !! the calibration
        integer, intent(in) :: lu                    !! listing unit
        real(wp), intent(out) :: vbest(:)            !! fitted parameter values
        real(wp), intent(out) :: jbest               !! objective there
        integer, intent(out) :: nevals               !! model evaluations (each runs every case)
        real(wp), allocatable :: design(:, :)
        real(wp) :: u0(size(cal%sw(1)%params)), ubest(size(u0)), j, jstart, lmax, lp
        type(score_t) :: sc(size(cal%sw))
        logical :: ok
        integer :: r, k, nnm
        associate (par => cal%sw(1)%params)
            write (lu, '(a)') 'CALIBRATION: '//trim(cal%title)
            write (lu, '(a,i0,a,i0,a,i0)') 'cases ', size(cal%sw), ', parameters ', size(par), ', seed ', cal%seed
            write (lu, '(a,es10.3,a,es10.3,a,es10.3)') 'objective J = (1 - R) + W P + WT T; W ', cal%peak_weight, &
                ', WT ', cal%time_weight, ', PEAK MARGIN M ', cal%peak_margin
            if (cal%max_evals == 0) then                 ! score the decks as they are, or at VALUES
                vbest = par%nominal
                if (size(cal%values) == size(par)) vbest = cal%values
                call evaluate(cal, vbest, jbest, sc, ok, lmax, lp)
                nevals = 1
                call score_report(cal, sc, jbest, lu)
                call rest_report(lmax, lp)
                return
            end if
            design = sweep_design(cal%sw(1))
            jstart = huge(one)
            nevals = 0
            do r = 1, size(design, 2)
                call evaluate(cal, design(:, r), j, sc, ok)
                nevals = nevals + 1
                call report('start', nevals, j, design(:, r))
                if (j < jstart) then
                    jstart = j
                    u0 = [(unit_of(par(k), design(k, r)), k=1, size(par))]
                end if
            end do
            call restarted_nelder_mead(obj, u0, 0.15_wp, max(cal%max_evals - nevals, size(par) + 2), 1.0e-4_wp, &
                                       ubest, jbest, nnm)
            vbest = values_of(ubest)
            write (lu, '(a,f9.5,a,i0,a)') 'BEST OBJECTIVE ', jbest, ' AFTER ', nevals, ' EVALUATIONS'
            call evaluate(cal, vbest, j, sc, ok, lmax, lp)
            call score_report(cal, sc, j, lu)
            call rest_report(lmax, lp)
            do k = 1, size(par)
                write (lu, '(a,a10,a,a10,a,es12.5,a,es12.5,a)') 'PARAM ', par(k)%name, ' = ', field_text(vbest(k)), &
                    '   (bounds ', par(k)%low, ' to ', par(k)%high, ')'
            end do
        end associate
    contains
        function obj(u) result(f)
            real(wp), intent(in) :: u(:)
            real(wp) :: f
            real(wp) :: v(size(u))
            type(score_t) :: s(size(cal%sw))
            logical :: good
            v = values_of(u)
            call evaluate(cal, v, f, s, good)
            nevals = nevals + 1
            call report('nelder', nevals, f, v)
        end function obj

        function values_of(u) result(v)
            real(wp), intent(in) :: u(:)
            real(wp) :: v(size(u))
            character(len=10) :: txt
            integer :: i
            do i = 1, size(u)
                v(i) = spread_value(cal%sw(1)%params(i), u(i))
                txt = field_text(v(i))
                if (cal%sw(1)%params(i)%kind == par_field) read (txt, *) v(i)
            end do
        end function values_of

        subroutine rest_report(lmax, lp)
            real(wp), intent(in) :: lmax, lp
            write (lu, '(a,es10.3,a)') 'LARGEST REAL PART AT REST ', lmax, ' 1/S'
            if (cal%passive .and. lp < huge(one)) &
                write (lu, '(a,es10.3,a)') 'LARGEST REAL PART AT REST WITHOUT MUSCLES ', lp, ' 1/S'
        end subroutine rest_report

        subroutine report(stage, n, f, v)
            character(len=*), intent(in) :: stage
            integer, intent(in) :: n
            real(wp), intent(in) :: f, v(:)
            integer :: i
            write (lu, '(a8,i6,f10.5,*(1x,a10))') stage, n, f, (field_text(v(i)), i=1, size(v))
            flush (lu)
        end subroutine report
    end subroutine calibrate

    !> The ratings and peaks of every case, three significant digits.
    subroutine score_report(cal, sc, j, lu)
        type(calibration_t), intent(in) :: cal
        type(score_t), intent(in) :: sc(:)
        real(wp), intent(in) :: j
        integer, intent(in) :: lu
        integer :: c, k
        write (lu, '(a,f8.4)') 'OBJECTIVE J = ', j
        do c = 1, size(sc)
            write (lu, '(a,a,a,f7.4)') 'CASE ', trim(cal%decks(c)), ': MEAN RATING ', &
                sum(sc(c)%rating)/size(cal%channels)
            do k = 1, size(cal%channels)
                write (lu, '(2x,a10,a,f6.3,a,f6.3,a,f6.3)') cal%channels(k)%name, ' RATING ', sc(c)%rating(k), &
                    '  C ', sc(c)%corridor(k), '  X ', sc(c)%xcorr(k)
            end do
            do k = 1, size(cal%peaks)
                write (lu, '(2x,a16,a,es10.3,a,f6.1,a,es10.3,a,es9.2,a,f6.1,a,f5.1,a,f6.2)') cal%peaks(k)%name, &
                    ' MODEL ', sc(c)%peak(k), ' AT ', sc(c)%time(k), ' MS; VOLUNTEERS ', cal%vol(c)%peak_mean(k), &
                    ' +- ', cal%vol(c)%peak_sd(k), ' AT ', cal%vol(c)%time_mean(k), ' +- ', cal%vol(c)%time_sd(k), &
                    '; Z ', sc(c)%z(k)
            end do
        end do
    end subroutine score_report

    !> Run every case of the calibration at parameter values v: the rated
    !! channels at the volunteers' times, y(:, :, case); ok false when a run fails.
    subroutine member_histories(cal, v, y, ok)
        type(calibration_t), intent(in) :: cal   !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp), intent(out) :: y(:, :, :)          !! (nt, nchannel, ncase)
        logical, intent(out) :: ok               !! every run complete
        type(case_t) :: cs
        type(run_result_t) :: res
        type(channel_set_t) :: ch
        integer :: c, stat, lu
        character(len=msglen) :: msg
        ok = .true.
        y = zero
        do c = 1, size(cal%sw)
            call sweep_member_case(cal%sw(c), v, cs, stat, msg)
            if (stat /= stat_ok) then
                ok = .false.; return
            end if
            open (newunit=lu, file='/dev/null', action='write')
            block
                type(run_state_t) :: run         ! a fresh run object for every case
                call run%execute(cs, lu, '', res, keep_samples=.true.)
            end block
            close (lu)
            if (res%exit_code /= exit_ok) then
                ok = .false.; return
            end if
            call channels_define(cs, ch)
            y(1:size(cal%vol(c)%t), :, c) = rated_histories(cal, cal%vol(c)%t, ch%name, cs%t_start, cs%sample_dt, &
                                                             res%samples)
        end do
    end subroutine member_histories

    !> The rated channels of a run (the CHANNEL cards), filtered with the
    !! calibration's CFC class and interpolated to the volunteers' times.
    function rated_histories(cal, tv, names, t0, dt, samples) result(y)
        type(calibration_t), intent(in) :: cal   !! the calibration (its channels and filter)
        real(wp), intent(in) :: tv(:)                !! the volunteers' times [ms]
        character(len=*), intent(in) :: names(:)     !! channel names of the rows of samples
        real(wp), intent(in) :: t0               !! first sample time [s]
        real(wp), intent(in) :: dt               !! sample interval [s]
        real(wp), intent(in) :: samples(:, :)        !! (nchannel, nsample)
        real(wp) :: y(size(tv), size(cal%channels))
        real(wp) :: f(size(samples, 2)), tm(size(samples, 2))
        integer :: k, i
        do i = 1, size(tm)
            tm(i) = 1000*(t0 + (i - 1)*dt)
        end do
        do k = 1, size(cal%channels)
            call cfc_filter(samples(findloc(names, cal%channels(k)%name, dim=1), :), dt, cal%cfc, f)
            y(:, k) = resample(tv, tm, f)
        end do
    end function rated_histories

end module hn_calibrate
