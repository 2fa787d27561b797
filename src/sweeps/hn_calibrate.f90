!> Calibration as code: fit named deck parameters (the PARAM cards of the
!! sweep deck: FAMILY scale factors, BODY scales, FIELDn values), within
!! their bounds, to cases of any kind -- volunteers (DATA a directory of
!! their runs), a reference (DATA a reference CSV: a specimen corridor's
!! midline, a segment test's mean) or published peaks (DATA a CSV whose
!! header is peak,mean,sd[,time_mean,time_sd]: a severity whose paper gives
!! the volunteers' peaks alone) -- by minimising the weighted mean over
!! the cases (CASE F7, default 1) of
!!
!!   J_c = (1 - R_c) + w P_c + wt T_c,
!!
!! R_c the case's mean rating of its rated channels by the RATING card's
!! metric (F5): CORA (the default) the CORA-style rating (hn_rating),
!! ISO18571 the overall ISO/TS 18571 rating (hn_iso18571, the formulas of
!! objective-rating-metrics) against the volunteers' mean curve on the
!! RATING window, or the reference curve on the rows it is given. A
!! volunteer case rates the deck's CHANNEL cards (CFC filtered, as the
!! volunteers' runs), a reference case the columns of its CSV as its
!! RATED cards map them to model channels (unfiltered: the reference is
!! as digitised). P_c the mean over the case's peaks
!! (PEAK cards) of max(0, |z| - (1 - m)), z the peak's distance from the
!! volunteers' mean in SDs and m a margin inside the 1 SD band, T the mean
!! over the same peaks of max(0, |dt|/tol - (1 - m)), dt the peak time's
!! distance from the volunteers' mean time and tol the peak-time tolerance
!! of the RATING card (the same margin keeps the times off its edge;
!! a reference case has no peaks: P_c = T_c = 0; a case of published
!! peaks has no rated curve, R_c = 1, and its P_c and T_c are over the
!! peaks its table gives, against the table's means and SDs); w
!! (default 0.02), wt (default 0) and m (default 0) are fields 5, 6 and 7
!! of the FIT card; subject to the model standing at rest: a parameter set
!! whose start state (posture held, the bracing activation) has an
!! eigenvalue with real part above -1 1/s in any case (hn_rest_modes) is
!! not run and gets J = 2 + 0.1 s (lmax + 1) (volunteer cases only: a
!! reference case is held as its deck holds it; with STANDING cards, a set
!! that moves a joint of a standing deck's run at rest more than its bound
!! instead, J = 2 + 0.1 (r - 1), r the largest ratio of excursion to
!! bound); with a PASSIVE card, nor is a
!! set whose neck stands without its muscles (largest real part at rest,
!! muscles off, below the card's limit, default 0: the osteoligamentous
!! column buckles under far less than the head's weight), which gets
!! J = 2 + 0.1 s (limit - lp). With a RANGES card of weight wr, J_c gains
!! wr G_c, G_c the sum over the joints' ranges (ROM cards) of
!! max(0, e_k/e_m - (1 - mr)), e_k the joint's largest excess beyond its
!! physiological range in the run, e_m the margin past which a run warns
!! (hn_joint_limits range_margin, 5 deg) and mr a margin kept inside it
!! (RANGES F2, default 0): a fit kept inside the ranges the runs are
!! checked against. The study itself (the volunteer files, the
!! channels they are compared with, the rating window, the filter, the
!! peaks and their windows) is the deck's RATING, CHANNEL and PEAK cards;
!! nothing of it is compiled in.
!! Optimizer (hn_optimize): a Latin hypercube of starting points (seeded)
!! and Nelder-Mead from the best of them, restarted about its best point
!! while a restart gains more than 1e-4, in the unit cube of the parameter
!! ranges (LOG ranges in logarithms), points clamped to the bounds.
!! Deterministic: the same deck gives the same fit on every machine.
!! Member runs are those of the sweep (sweep_member_case, run_state_t):
!! no result file, the listing to /dev/null; a volunteer case sampled at
!! 0.1 ms or finer (its CFC filter), a reference case at its deck's OUTPUT
!! interval (the curves its result file would hold: a segment test's 10 ms).
module hn_calibrate
    use hn_kinds, only: wp, zero, one, msglen, deg
    use hn_status, only: stat_ok, stat_bad_input
    use hn_case, only: case_t, deck_line_t, path_len
    use hn_deck_state, only: real_str
    use hn_deck_reader, only: deck_reader_t, read_card_images, int_str
    use hn_sweep, only: sweep_t, sweep_param_t, read_sweep_lines, sweep_member_case, sweep_design, spread_value, &
                        field_text, par_field, param_target_text
    use hn_run, only: run_state_t, run_result_t, exit_ok
    use hn_channels, only: channel_set_t, channels_define, chname_len
    use hn_filters, only: cfc_filter
    use hn_tables, only: resample
    use hn_optimize, only: restarted_nelder_mead
    use hn_rating, only: peak_t, corridor_t, score_t, score_curves, window_samples, max_lag, cora_rating, curve_peak
    use hn_volunteer_data, only: data_channel_t, read_volunteers, reference_data_t, read_reference_csv, &
                                 peak_table_t, is_peak_table, read_peak_table
    use hn_iso18571, only: iso18571_rating_t, iso18571_rating, iso18571_min_samples, iso18571_dt
    use hn_prestrain, only: prestrain_t, settle_prestrain
    use hn_rest_modes, only: rest_mode_t, rest_modes
    use hn_model, only: model_t
    use hn_joint_limits, only: range_margin
    implicit none
    private

    public :: calibration_t, reference_case_t, read_calibration, evaluate, calibrate, member_histories, range_score
    integer, parameter, public :: metric_cora = 1, metric_iso18571 = 2   !! RATING F5

    real(wp), parameter :: failed_objective = 10.0_wp        !! J of a parameter set whose run fails
    real(wp), parameter :: rest_margin = -1.0_wp             !! largest real part allowed at rest [1/s]
    real(wp), parameter :: unstable_objective = 2.0_wp       !! J of a set unstable at rest, at the margin
    real(wp), parameter :: unstable_slope = 0.1_wp           !! its growth per 1/s beyond the margin [s]
    integer, parameter :: peak_name_len = 16                 !! longest peak name (PEAK card, columns 51-80)

    !> The rated channels of a reference case (DATA a reference CSV): its
    !! curves and, per rated channel (RATED card, or each column of the
    !! CSV under its own name), the model curve compared with it:
    !! scale (channel - minus), less its value at the start with START,
    !! filtered by its CFC class when one is given.
    type :: reference_case_t
        logical :: on = .false.                         !! the case's DATA is a reference CSV
        type(reference_data_t) :: data                  !! its curves
        character(len=10), allocatable :: column(:)     !! (rated) the CSV column (RATED F1)
        integer, allocatable :: col(:)                  !! (rated) its number in data
        character(len=10), allocatable :: channel(:)    !! (rated) the model channel (F2)
        real(wp), allocatable :: scale(:)               !! (rated) its factor (F3, default 1)
        character(len=10), allocatable :: minus(:)      !! (rated) a channel subtracted (F4, '' none)
        logical, allocatable :: from_start(:)           !! (rated) less its value at the start (F5 START)
        logical, allocatable :: as_samples(:)           !! (rated) its rows the rating's 10 kHz samples (F6 SAMPLES)
        real(wp), allocatable :: cfc(:)                 !! (rated) the model curve's CFC class [Hz] (F7; 0: unfiltered)
    end type reference_case_t

    !> A standing case (STANDING card): a deck of the model at rest, its
    !! parameters bound as a case's; the model stands when no joint rotation
    !! of its run moves more than the bound from its start.
    type :: standing_case_t
        character(len=path_len) :: deck = ''   !! the deck (STANDING columns 11-70)
        real(wp) :: bound = zero               !! the largest excursion allowed (STANDING F7) [deg]
        type(sweep_t) :: sw                    !! the PARAM cards bound to its deck
    end type standing_case_t

    !> The joints of one run past their physiological ranges (ROM cards).
    type, public :: range_score_t
        real(wp) :: term = zero      !! G_c: sum of max(0, e_k/e_m - (1 - mr)) [-]
        integer :: past = 0          !! joints past their range by more than e_m (the run's warnings)
        real(wp) :: largest = zero   !! the largest excess [rad]
    end type range_score_t

    !> A calibration: its cases (deck, volunteers or reference, weight, the
    !! sweep that binds the parameters to that deck), the study (rated
    !! channels, peaks, rating window, filter, metric) and the optimizer's
    !! settings.
    type :: calibration_t
        character(len=80) :: title = ''
        character(len=path_len), allocatable :: decks(:), data(:)
        real(wp), allocatable :: weight(:)          !! (case) its weight in the objective (CASE F7)
        type(sweep_t), allocatable :: sw(:)
        type(sweep_param_t), allocatable :: par(:)  !! the parameters, each as the first case binding it binds it
        type(corridor_t), allocatable :: vol(:)     !! the volunteers of each case (volunteer cases)
        type(reference_case_t), allocatable :: ref(:)   !! the reference of each case (reference cases: ref(c)%on)
        type(peak_table_t), allocatable :: pub(:)   !! the published peaks of each case (peak-table cases: pub(c)%on)
        integer :: metric = metric_cora             !! RATING F5: the rating of the objective
        character(len=path_len) :: curves = ''      !! CURVES card: the rated curves' CSV of an evaluation alone
        type(data_channel_t), allocatable :: channels(:)   !! CHANNEL cards: the rated channels
        type(peak_t), allocatable :: peaks(:)       !! PEAK cards (curve: a channel number)
        real(wp) :: window(2) = zero                !! RATING F1, F2: the rated times [ms]
        real(wp) :: cfc = zero                      !! RATING F3: CFC class of model and volunteer channels [Hz]
        real(wp) :: time_tolerance = zero           !! RATING F4: peak-time tolerance of the goal [ms]
        integer :: max_evals = 200, nstart = 8, seed = 1
        real(wp) :: peak_weight = 0.02_wp           !! w of the objective (FIT F5)
        real(wp) :: time_weight = zero              !! wt of the objective (FIT F6)
        real(wp) :: peak_margin = zero              !! m of the objective: P counts |z| above 1 - m (FIT F7)
        real(wp) :: range_weight = zero             !! wr of the objective (RANGES F1): the joints past their ranges
        real(wp) :: range_inside = zero             !! mr: G counts each excess above (1 - mr) e_m (RANGES F2)
        logical :: passive = .false.                !! PASSIVE card: the neck without its muscles must not stand
        real(wp) :: passive_limit = zero            !! its largest real part at rest must be above this (PASSIVE F1) [1/s]
        real(wp), allocatable :: values(:)          !! VALUES cards: the point scored when max_evals = 0
        type(standing_case_t), allocatable :: stand(:)   !! STANDING cards: the motion at rest in place of the margin
    end type calibration_t

    !> What the reading of a calibration deck keeps from card to card: the
    !! deck itself and where each card was, for the checks across cards
    !! and the located messages of each case's binding to its sweep.
    type :: calibration_deck_t
        type(deck_reader_t) :: rd                        !! the deck: card images, located field access, the first error
        type(deck_line_t), allocatable :: params(:)      !! the PARAM cards, the sweep of every case
        character(len=10), allocatable :: optional(:)    !! (OPTIONAL card fields) parameters bound only where present
        integer, allocatable :: optional_line(:)         !! (the same) the line of its OPTIONAL card
        integer, allocatable :: data_line(:)             !! (case) the line of its DATA card
        logical, allocatable :: is_ref(:)                !! (DATA card) it names a reference CSV
        logical, allocatable :: is_pub(:)                !! (DATA card) it names a table of published peaks
        integer, allocatable :: rated_line(:)            !! (RATED card) its line
        integer, allocatable :: rated_case(:)            !! (RATED card) the case it rates
        integer, allocatable :: channel_line(:)          !! (CHANNEL card) its line
        integer, allocatable :: peak_line(:)             !! (PEAK card) its line
        character(len=10), allocatable :: peak_channel(:)    !! (PEAK card) the channel it names (F1)
        integer :: nfit = 0                              !! FIT cards read
        integer :: rating_line = 0                       !! the line of the RATING card (0: none yet)
        integer :: values_line = 0                       !! the line of the first VALUES card (0: none)
    end type calibration_deck_t

contains

    !> Read a calibration deck: TITLE; CASE path (columns 11-70) [weight
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
    !! that point written as CSV). Each case's parameters are bound to its own deck through a
    !! sweep (same checks); every CHANNEL must be a channel of every case
    !! deck, and every volunteer file is read (docs/sweeps.md).
    subroutine read_calibration(path, source, cal, stat, errmsg, include_path)
        character(len=*), intent(in) :: path     !! the calibration deck's file
        character(len=*), intent(in) :: source   !! its name in messages
        type(calibration_t), intent(out) :: cal  !! the calibration
        integer, intent(out) :: stat             !! stat_ok, or stat_bad_input
        character(len=msglen), intent(out) :: errmsg !! the deck line, columns and what was expected
        character(len=*), intent(in), optional :: include_path(:)  !! directories searched for CASE decks and INCLUDE files
        type(calibration_deck_t) :: st
        integer :: i
        st%rd%top = source
        if (present(include_path)) st%rd%search = include_path
        call read_card_images(st%rd, path, source, 0)
        allocate (cal%decks(0), cal%data(0), cal%values(0), cal%channels(0), cal%peaks(0), cal%weight(0), cal%stand(0))
        allocate (st%params(0), st%optional(0), st%optional_line(0), st%channel_line(0), st%peak_line(0), &
                  st%data_line(0), st%peak_channel(0), &
                  st%rated_line(0), st%rated_case(0), st%is_ref(0), st%is_pub(0))
        do i = 1, st%rd%nlines
            if (st%rd%failed()) exit
            select case (st%rd%key(i))
            case ('TITLE'); call read_title_card(st, cal, i)
            case ('CASE'); call read_case_card(st, cal, i)
            case ('DATA'); call read_data_card(st, cal, i)
            case ('RATED'); call read_rated_card(st, cal, i)
            case ('FIT'); call read_fit_card(st, cal, i)
            case ('RATING'); call read_rating_card(st, cal, i)
            case ('CHANNEL'); call read_channel_card(st, cal, i)
            case ('PEAK'); call read_peak_card(st, cal, i)
            case ('PARAM'); call read_param_card(st, i)
            case ('OPTIONAL'); call read_optional_card(st, i)
            case ('PASSIVE'); call read_passive_card(st, cal, i)
            case ('STANDING'); call read_standing_card(st, cal, i)
            case ('RANGES'); call read_ranges_card(st, cal, i)
            case ('VALUES'); call read_values_card(st, cal, i)
            case ('CURVES'); call read_curves_card(st, cal, i)
            case ('END'); exit
            case default; call unknown_card(st, i)
            end select
        end do
        call check_calibration_cards(st, cal, source)
        stat = st%rd%stat; errmsg = st%rd%errmsg
        if (stat /= stat_ok) return
        call bind_cases(st, cal, path, source, stat, errmsg, include_path)
    end subroutine read_calibration

    !> TITLE: the calibration's title (columns 11-80).
    pure subroutine read_title_card(st, cal, i)
        type(calibration_deck_t), intent(in) :: st     !! the deck and its cards so far
        type(calibration_t), intent(inout) :: cal      !! the calibration the card fills
        integer, intent(in) :: i                       !! the card's line
        cal%title = adjustl(st%rd%lines(i)%text(11:80))
    end subroutine read_title_card

    !> CASE: a case deck (columns 11-70) and its weight (F7, default 1).
    subroutine read_case_card(st, cal, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        type(calibration_t), intent(inout) :: cal      !! the calibration the card fills
        integer, intent(in) :: i                       !! the card's line
        real(wp) :: w
        cal%decks = [character(len=path_len) :: cal%decks, adjustl(st%rd%lines(i)%text(11:70))]
        call st%rd%real(i, 7, 'case weight', '-', w, 1.0e-6_wp, 1.0e6_wp, default=one)
        cal%weight = [cal%weight, w]
    end subroutine read_case_card

    !> DATA: the last case's volunteer directory or reference CSV (a name
    !! ending in .csv), found as an INCLUDE file is: next to the calibration
    !! deck, in the working directory, then on the include path (-I,
    !! HHNECK_PATH); one DATA card after each CASE card.
    subroutine read_data_card(st, cal, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        type(calibration_t), intent(inout) :: cal      !! the calibration the card fills
        integer, intent(in) :: i                       !! the card's line
        character(len=:), allocatable :: dname, found
        character(len=msglen) :: msg
        if (size(cal%data) /= size(cal%decks) - 1) then
            call st%rd%fail(st%rd%where(i)//' (DATA card): expected one DATA card after each CASE card')
            return
        end if
        dname = trim(adjustl(st%rd%lines(i)%text(11:80)))
        st%is_ref = [st%is_ref, is_csv(dname)]
        call st%rd%find_file(dname, st%rd%lines(i)%source, found, msg, directory=.not. st%is_ref(size(st%is_ref)))
        if (len(found) == 0) then
            call st%rd%fail(st%rd%where(i)//' (DATA card): '//trim(msg))
            return
        end if
        cal%data = [character(len=path_len) :: cal%data, found]
        st%data_line = [st%data_line, i]
        ! a CSV whose header starts with `peak`: published peaks, not curves
        st%is_pub = [st%is_pub, st%is_ref(size(st%is_ref)) .and. is_peak_table(found)]
        if (st%is_pub(size(st%is_pub))) st%is_ref(size(st%is_ref)) = .false.
    end subroutine read_data_card

    !> RATED: a card of the last case, whose DATA card names a reference
    !! CSV; its fields are read with the CSV (rated_columns).
    subroutine read_rated_card(st, cal, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        type(calibration_t), intent(in) :: cal         !! the calibration so far (its cases)
        integer, intent(in) :: i                       !! the card's line
        if (size(cal%decks) == 0 .or. size(st%is_ref) /= size(cal%decks)) then
            call st%rd%fail(st%rd%where(i)//', columns 1-8 (RATED card): expected RATED cards after the DATA '// &
                            'card of a case (a reference CSV)')
            return
        end if
        if (.not. st%is_ref(size(st%is_ref))) then
            call st%rd%fail(st%rd%where(i)//', columns 1-8 (RATED card): the DATA card before it names a '// &
                            'directory of volunteer runs; expected RATED cards after the DATA card of a '// &
                            'reference CSV (a name ending in .csv)')
            return
        end if
        st%rated_line = [st%rated_line, i]
        st%rated_case = [st%rated_case, size(cal%decks)]
    end subroutine read_rated_card

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
    !! [peak-time-weight [peak-margin]]] (one card: check_calibration_cards).
    subroutine read_fit_card(st, cal, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        type(calibration_t), intent(inout) :: cal      !! the calibration the card fills
        integer, intent(in) :: i                       !! the card's line
        character(len=10) :: s
        associate (rd => st%rd)
            st%nfit = st%nfit + 1
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
    end subroutine read_fit_card

    !> RATING window-start window-end CFC-class peak-time-tolerance [CORA
    !! or ISO18571]: one card.
    subroutine read_rating_card(st, cal, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        type(calibration_t), intent(inout) :: cal      !! the calibration the card fills
        integer, intent(in) :: i                       !! the card's line
        character(len=10) :: opt
        associate (rd => st%rd)
            if (st%rating_line > 0) then
                call rd%fail(rd%where(i)//', columns 1-8 (RATING card): found a second RATING card; '// &
                             'expected one (the RATING card at '//rd%where(st%rating_line)//' has it)')
                return
            end if
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
    end subroutine read_rating_card

    !> CHANNEL channel VALUE-or-RATE [DEG-RAD] file (columns 41-80): a
    !! rated channel, one card per channel.
    subroutine read_channel_card(st, cal, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        type(calibration_t), intent(inout) :: cal      !! the calibration the card fills
        integer, intent(in) :: i                       !! the card's line
        type(data_channel_t) :: dc
        character(len=10) :: opt
        integer :: k
        associate (rd => st%rd)
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
        end associate
        cal%channels = [cal%channels, dc]
        st%channel_line = [st%channel_line, i]
    end subroutine read_channel_card

    !> PEAK channel MIN-or-MAX window-start window-end name (columns
    !! 51-80): a peak, one card per name; its channel, a CHANNEL card's
    !! before or after it, is found by check_calibration_cards.
    subroutine read_peak_card(st, cal, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        type(calibration_t), intent(inout) :: cal      !! the calibration the card fills
        integer, intent(in) :: i                       !! the card's line
        type(peak_t) :: pk
        character(len=10) :: s, opt
        character(len=:), allocatable :: ctext
        integer :: k
        associate (rd => st%rd)
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
        end associate
        cal%peaks = [cal%peaks, pk]
        st%peak_line = [st%peak_line, i]
        st%peak_channel = [character(len=10) :: st%peak_channel, s]
    end subroutine read_peak_card

    !> PARAM: a fitted parameter, kept for each case's sweep (bind_cases).
    pure subroutine read_param_card(st, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        integer, intent(in) :: i                       !! the card's line
        st%params = [st%params, st%rd%lines(i)]
    end subroutine read_param_card

    !> OPTIONAL: up to 7 PARAM names (F1-F7), each bound in the cases whose
    !! deck has its target (family, body or card) and left out of the
    !! others, e.g. the muscles' parameters beside segment cases that have
    !! no muscles; every one must be bound in some case (bind_cases).
    subroutine read_optional_card(st, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        integer, intent(in) :: i                       !! the card's line
        character(len=10) :: name
        integer :: f
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
    end subroutine read_optional_card

    !> PASSIVE [limit]: a set whose neck stands without its muscles is not run.
    subroutine read_passive_card(st, cal, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        type(calibration_t), intent(inout) :: cal      !! the calibration the card fills
        integer, intent(in) :: i                       !! the card's line
        cal%passive = .true.
        call st%rd%real(i, 1, 'largest real part at rest without muscles', '1/s', cal%passive_limit, &
                        -100.0_wp, 100.0_wp, default=zero)
    end subroutine read_passive_card

    !> STANDING deck (columns 11-70) bound (F7, deg): a run of the deck, the
    !! model at rest, must keep every joint rotation within the bound of its
    !! start; with STANDING cards they judge standing in place of the
    !! volunteer cases' linear margin at rest.
    subroutine read_standing_card(st, cal, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        type(calibration_t), intent(inout) :: cal      !! the calibration the card fills
        integer, intent(in) :: i                       !! the card's line
        type(standing_case_t) :: sc
        sc%deck = adjustl(st%rd%lines(i)%text(11:70))
        if (len_trim(sc%deck) == 0) then
            call st%rd%fail(st%rd%where(i)//', columns 11-70 (STANDING card): found no deck; expected the '// &
                            'deck of the model at rest')
            return
        end if
        call st%rd%real(i, 7, 'largest excursion at rest', 'deg', sc%bound, 1.0e-3_wp, 90.0_wp)
        if (st%rd%failed()) return
        cal%stand = [cal%stand, sc]
    end subroutine read_standing_card

    !> RANGES weight [margin]: the joints past their ranges in J.
    subroutine read_ranges_card(st, cal, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        type(calibration_t), intent(inout) :: cal      !! the calibration the card fills
        integer, intent(in) :: i                       !! the card's line
        call st%rd%real(i, 1, 'range weight', '-', cal%range_weight, zero, 1.0e3_wp)
        call st%rd%real(i, 2, 'range margin', '-', cal%range_inside, zero, 0.9_wp, default=zero)
    end subroutine read_ranges_card

    !> VALUES: up to 7 parameter values, in PARAM order (their count:
    !! check_calibration_cards).
    subroutine read_values_card(st, cal, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        type(calibration_t), intent(inout) :: cal      !! the calibration the card fills
        integer, intent(in) :: i                       !! the card's line
        integer :: f
        real(wp) :: x
        if (st%values_line == 0) st%values_line = i
        do f = 1, 7
            if (st%rd%is_blank(i, f)) cycle
            call st%rd%real(i, f, 'parameter value', '-', x, -1.0e30_wp, 1.0e30_wp)
            cal%values = [cal%values, x]
        end do
    end subroutine read_values_card

    !> CURVES file (columns 11-80): the rated curves of an evaluation alone.
    subroutine read_curves_card(st, cal, i)
        type(calibration_deck_t), intent(in) :: st     !! the deck and its cards so far
        type(calibration_t), intent(inout) :: cal      !! the calibration the card fills
        integer, intent(in) :: i                       !! the card's line
        cal%curves = st%rd%text(i, 11)
    end subroutine read_curves_card

    !> A card the calibration deck does not have.
    subroutine unknown_card(st, i)
        type(calibration_deck_t), intent(inout) :: st  !! the deck and its cards so far
        integer, intent(in) :: i                       !! the card's line
        call st%rd%fail(st%rd%where(i)//', columns 1-8: found "'//trim(st%rd%key(i))// &
                        '"; expected TITLE, CASE, DATA, RATED, FIT, RATING, CHANNEL, PEAK, PARAM, OPTIONAL, '// &
                        'PASSIVE, STANDING, RANGES, VALUES, CURVES or END')
    end subroutine unknown_card

    !> The checks across cards, after the last: each PEAK card's channel a
    !! CHANNEL card's (its curve), at least one CASE each with its DATA, one
    !! FIT and one RATING card, CHANNEL and PEAK cards when a case has
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
            if (.not. rd%failed() .and. (size(cal%decks) == 0 .or. size(cal%data) /= size(cal%decks) .or. &
                                         st%nfit /= 1 .or. st%rating_line == 0)) &
                call rd%fail(source//': expected at least one CASE card, each followed by its DATA card, one FIT '// &
                             'card and one RATING card')
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
            if (.not. rd%failed() .and. st%values_line > 0 .and. size(cal%values) /= size(st%params)) &
                call rd%fail(rd%where(st%values_line)//' (VALUES card): found '//trim(int_str(size(cal%values)))// &
                             ' values on the VALUES cards; expected one per PARAM card, '// &
                             trim(int_str(size(st%params))))
        end associate
    end subroutine check_calibration_cards

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

    !> The sampling interval ISO 18571 takes the rows of rated channel m
    !! of a reference case at [s]: its CSV's time step, or with SAMPLES
    !! (RATED F6) the rating's own 0.1 ms (each row one sample: a curve
    !! whose abscissa is not time, as a moment-rotation curve read on a
    !! moment ramp, is rated as the catalogue rates it, not resampled).
    pure real(wp) function rated_interval(rf, m) result(dt)
        type(reference_case_t), intent(in) :: rf   !! the case's reference, its RATED cards read
        integer, intent(in) :: m                   !! the rated channel
        if (rf%as_samples(m)) then
            dt = iso18571_dt
        else
            dt = (rf%data%t(2) - rf%data%t(1))*1.0e-3_wp
        end if
    end function rated_interval

    !> A DATA name ending in .csv (any case): a reference CSV.
    pure logical function is_csv(name)
        character(len=*), intent(in) :: name   !! the DATA card's name
        integer :: n
        n = len_trim(name)
        is_csv = .false.
        if (n > 4) is_csv = any(name(n - 3:n) == ['.csv', '.CSV', '.Csv'])
    end function is_csv

    !> A card image of a case's sweep, made by the calibration (line 0).
    pure function line_of(text, source) result(l)
        character(len=*), intent(in) :: text     !! the card
        character(len=*), intent(in) :: source   !! the calibration deck's name in messages
        type(deck_line_t) :: l
        l%text = text
        l%source = source
        l%line = 0
    end function line_of

    !> n as a left-justified field of 10 columns.
    pure function int_field(n) result(f)
        integer, intent(in) :: n   !! the number
        character(len=10) :: f
        write (f, '(i0)') n
    end function int_field

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

    !> Largest real part of the eigenvalues at rest (hn_rest_modes: the
    !! start state of every volunteer case, posture held as the case holds
    !! it; a living subject's braced neck stands) over the volunteer cases
    !! at parameter values v [1/s] (-huge without one), with the muscles (lmax) and,
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
        integer :: c, stat, f
        character(len=msglen) :: msg
        lmax = -huge(one)
        lp = merge(-huge(one), huge(one), cal%passive)
        do c = 1, size(cal%sw)
            if (cal%ref(c)%on) cycle            ! a reference case is held as its deck holds it
            call sweep_member_case(cal%sw(c), v, cs, stat, msg)
            if (stat == stat_ok) call case_rest_modes(cs, modes, stat, msg)
            if (stat /= stat_ok) then
                lmax = huge(one); return
            end if
            if (size(modes) > 0) lmax = max(lmax, modes(1)%re)
            if (.not. cal%passive) cycle
            do f = 1, size(cs%model%family)
                if (cs%model%family(f)%f%active_muscle()) cs%model%family_on(f) = .false.
            end do
            call case_rest_modes(cs, modes, stat, msg)
            if (stat /= stat_ok) then
                lp = huge(one)
            else if (size(modes) > 0 .and. lp < huge(one)) then
                lp = max(lp, modes(1)%re)
            end if
        end do
    end subroutine rest_growth

    !> The largest excursion of any joint rotation from its start [deg] in
    !! the run of each STANDING deck at parameter values v (its joint
    !! rotation channels alone, at the deck's OUTPUT interval); a run that
    !! cannot be built or does not complete counts as fallen (huge).
    function standing_excursions(cal, v) result(exc)
        type(calibration_t), intent(in) :: cal       !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp) :: exc(size(cal%stand))
        type(case_t) :: cs
        type(channel_set_t) :: chs
        type(run_result_t) :: res
        character(len=chname_len), allocatable :: joints(:)
        character(len=msglen) :: msg
        integer :: k, stat, lu, n
        exc = huge(one)
        do k = 1, size(cal%stand)
            call sweep_member_case(cal%stand(k)%sw, v, cs, stat, msg, deck_sampling=.true.)
            if (stat /= stat_ok) cycle
            call channels_define(cs, chs)
            joints = pack(chs%name, chs%group(:)(1:6) == 'JOINTS')
            if (size(joints) == 0) cycle
            open (newunit=lu, file='/dev/null', action='write')
            block
                type(run_state_t) :: run
                call run%execute(cs, lu, '', res, keep_samples=.true., only=joints)
            end block
            close (lu)
            if (res%exit_code /= exit_ok) cycle
            n = size(res%samples, 2)
            exc(k) = maxval(abs(res%samples(:, 1:n) - spread(res%samples(:, 1), 2, n)))
        end do
    end function standing_excursions

    !> The rest modes of a case at its start, held or settled as its run
    !! starts (HOLD POSTURE's forces, or HOLD PRESTRAIN's pre-strain of a
    !! copy of its model).
    subroutine case_rest_modes(cs, modes, stat, msg)
        type(case_t), intent(in) :: cs                          !! the case
        type(rest_mode_t), allocatable, intent(out) :: modes(:) !! its rest modes (rest_modes)
        integer, intent(out) :: stat                            !! stat_ok, or what failed
        character(len=msglen), intent(out) :: msg               !! what failed
        type(model_t) :: settled
        type(prestrain_t) :: ps
        if (.not. cs%hold_prestrain) then
            call rest_modes(cs%model, cs%t_start, cs%x0, cs%xd0, cs%hold_posture, modes, stat, msg)
            return
        end if
        settled = cs%model
        call settle_prestrain(settled, cs%t_start, cs%x0, cs%xd0, ps, stat, msg)
        if (stat == stat_ok) call rest_modes(settled, cs%t_start, cs%x0, cs%xd0, .false., modes, stat, msg)
    end subroutine case_rest_modes

    !> Objective J and the scores of every case for parameter values v. A
    !! parameter set whose model is not stable at rest with the margin
    !! (largest real part above rest_margin in any case: a braced neck
    !! stands) is not run: J = 2 + 0.1 s (lmax - rest_margin), worse than
    !! any stable set whose w P + wt T stays below 1, and decreasing
    !! towards stability. With STANDING cards their runs judge standing
    !! instead: a set that moves a joint of a standing case more than its
    !! bound (the largest ratio r of excursion to bound above 1) is not
    !! run, J = 2 + 0.1 (r - 1). With a PASSIVE card, nor is a set whose neck
    !! stands without its muscles (largest real part at rest below the
    !! card's limit): J = 2 + 0.1 s (limit - lp). Otherwise J is the
    !! weighted mean of the cases' J_c (the module's description); every
    !! case's channels are rated by both metrics (sc: CORA-style in
    !! rating, corridor, xcorr; ISO 18571 in iso), the RATING card's
    !! metric enters J. With `curves`, the rated curves (the samples each
    !! rating is given: reference and model) are written to that unit as
    !! CSV rows case,channel,time_ms,reference,model.
    subroutine evaluate(cal, v, j, sc, ok, growth, passive_growth, curves, ranges, standing)
        type(calibration_t), intent(in) :: cal       !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp), intent(out) :: j                   !! the objective
        type(score_t), intent(out) :: sc(:)          !! (ncase) ratings and peaks of each case
        logical, intent(out) :: ok                   !! every run complete
        real(wp), intent(out), optional :: growth    !! largest real part at rest over the cases [1/s]
        real(wp), intent(out), optional :: passive_growth !! the same without the muscles (PASSIVE card) [1/s]
        integer, intent(in), optional :: curves      !! unit of the rated curves' CSV (written when present)
        type(range_score_t), intent(out), optional :: ranges(:) !! (ncase) the joints past their ranges in each run
        real(wp), intent(out), optional :: standing(:)   !! (STANDING cards) each case's largest excursion at rest [deg]
        real(wp), allocatable :: y(:, :)
        real(wp) :: rsum, psum, tsum, gsum, wsum, lmax, lp, r, exc(size(cal%stand))
        type(range_score_t) :: rg
        integer :: c, k
        type(case_t) :: cs
        type(run_result_t) :: res
        type(channel_set_t) :: ch
        call rest_growth(cal, v, lmax, lp)
        if (present(growth)) growth = lmax
        if (present(passive_growth)) passive_growth = huge(one)
        if (size(cal%stand) > 0) then
            exc = standing_excursions(cal, v)
            if (present(standing)) standing = exc
            r = maxval(exc/cal%stand%bound)
            if (r > one) then
                ok = .false.
                j = rest_penalty(r - one)
                return
            end if
        else if (lmax > rest_margin) then
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
        j = failed_objective
        rsum = zero; psum = zero; tsum = zero; gsum = zero; wsum = zero
        do c = 1, size(cal%sw)
            call run_member(cal, c, v, cs, ch, res, ok)
            if (.not. ok) return
            rg = range_score(res%range_peak, cal%range_inside)
            if (present(ranges)) ranges(c) = rg
            gsum = gsum + cal%weight(c)*rg%term
            if (cal%ref(c)%on) then
                call score_reference(cal%ref(c), ch%name, cs%t_start, cs%sample_dt, res%samples, sc(c), c, curves)
            else if (cal%pub(c)%on) then
                call score_published(cal, c, ch%name, cs%t_start, cs%sample_dt, res%samples, sc(c))
                call add_peak_terms(cal, c, sc(c), cal%pub(c)%time_mean, cal%pub(c)%has, cal%pub(c)%has_time, &
                                    psum, tsum)
            else
                allocate (y(size(cal%vol(c)%t), size(cal%channels)))
                y = rated_histories(cal, cal%vol(c)%t, ch%name, cs%t_start, cs%sample_dt, res%samples)
                call score_curves(cal%vol(c), y, cal%window, cal%peaks, sc(c))
                call score_iso_volunteers(cal, c, y, sc(c), curves)
                deallocate (y)
                call add_peak_terms(cal, c, sc(c), cal%vol(c)%time_mean, [(.true., k=1, size(cal%peaks))], &
                                    [(.true., k=1, size(cal%peaks))], psum, tsum)
            end if
            rsum = rsum + cal%weight(c)*case_rating(cal, sc(c))
            wsum = wsum + cal%weight(c)
        end do
        j = (one - rsum/wsum) + (cal%peak_weight*psum + cal%time_weight*tsum + cal%range_weight*gsum)/wsum
    end subroutine evaluate

    !> Add case c's peak terms, weighted, to the sums of P and T: the mean
    !! over the peaks it has of max(0, |z| - (1 - m)), and of max(0, |t -
    !! t_mean|/tol - (1 - m)) over those of them with a time.
    pure subroutine add_peak_terms(cal, c, sc, time_mean, has, has_time, psum, tsum)
        type(calibration_t), intent(in) :: cal   !! the calibration (weights, margin, tolerance)
        integer, intent(in) :: c                 !! the case
        type(score_t), intent(in) :: sc          !! its scores (z and times of every peak)
        real(wp), intent(in) :: time_mean(:)     !! (peak) the volunteers' mean time [ms]
        logical, intent(in) :: has(:)            !! (peak) the case has the peak
        logical, intent(in) :: has_time(:)       !! (peak) and its time
        real(wp), intent(inout) :: psum          !! sum of the weighted P_c
        real(wp), intent(inout) :: tsum          !! sum of the weighted T_c
        psum = psum + cal%weight(c)*sum(max(zero, abs(sc%z) - (one - cal%peak_margin)), mask=has)/count(has)
        tsum = tsum + cal%weight(c)*sum(max(zero, abs(sc%time - time_mean)/cal%time_tolerance - &
                                            (one - cal%peak_margin)), mask=has_time)/count(has)
    end subroutine add_peak_terms

    !> The joints of a run past their physiological ranges: G, the sum over
    !! the ranges of max(0, e_k/e_m - (1 - m)) (e_k the largest excess of
    !! range k, e_m = range_margin, m the margin kept inside it), the number past
    !! the margin (those a run warns of) and the largest excess.
    pure function range_score(peak, m) result(rg)
        real(wp), intent(in) :: peak(:)          !! (range) largest excess beyond each range [rad]
        real(wp), intent(in) :: m                !! margin kept inside e_m, as a fraction of it
        type(range_score_t) :: rg
        rg%term = sum(max(zero, peak/range_margin - (one - m)))
        rg%past = count(peak > range_margin)
        rg%largest = maxval([zero, peak])
    end function range_score

    !> The mean rating of a case's channels by the calibration's metric.
    pure real(wp) function case_rating(cal, sc) result(r)
        type(calibration_t), intent(in) :: cal   !! the calibration (its metric)
        type(score_t), intent(in) :: sc          !! the case's scores
        if (size(sc%rating) == 0) then          ! published peaks: no curve to rate, J_c = w P_c + wt T_c
            r = one
        else if (cal%metric == metric_iso18571) then
            r = sum(sc%iso%overall)/size(sc%iso)
        else
            r = sum(sc%rating)/size(sc%rating)
        end if
    end function case_rating

    !> The first and last of the evenly spaced times t within the window.
    pure subroutine window_rows(t, window, i1, i2)
        real(wp), intent(in) :: t(:)             !! times [ms]
        real(wp), intent(in) :: window(2)        !! first and last time [ms]
        integer, intent(out) :: i1, i2           !! the rows (i2 < i1: none)
        i1 = findloc(t >= window(1) .and. t <= window(2), .true., dim=1)
        i2 = findloc(t >= window(1) .and. t <= window(2), .true., dim=1, back=.true.)
    end subroutine window_rows

    !> ISO 18571 of a volunteer case's rated curves y against the
    !! volunteers' mean on the RATING window (the samples there, at the
    !! volunteers' interval); the rated curves to unit `curves` when present.
    subroutine score_iso_volunteers(cal, c, y, sc, curves)
        type(calibration_t), intent(in) :: cal   !! the calibration
        integer, intent(in) :: c                 !! the case
        real(wp), intent(in) :: y(:, :)          !! (time, channel) the model's rated curves at the volunteers' times
        type(score_t), intent(inout) :: sc       !! its scores: iso filled
        integer, intent(in), optional :: curves  !! unit of the curves' CSV
        integer :: k, i1, i2, stat
        character(len=msglen) :: msg
        associate (vol => cal%vol(c))
            call window_rows(vol%t, cal%window, i1, i2)
            allocate (sc%iso(size(cal%channels)))
            do k = 1, size(cal%channels)
                call iso18571_rating(vol%mean(i1:i2, k), y(i1:i2, k), (vol%t(2) - vol%t(1))*1.0e-3_wp, sc%iso(k), &
                                     stat, msg)
                if (present(curves)) call write_curves(curves, c, cal%channels(k)%name, vol%t(i1:i2), &
                                                       vol%mean(i1:i2, k), y(i1:i2, k))
            end do
        end associate
    end subroutine score_iso_volunteers

    !> Score the rated channels of a reference case: each model curve
    !! (scale (channel - minus), less its start value with START, then
    !! filtered by its CFC class when it has one) at the
    !! reference's times on the rows it is given, by ISO 18571 and the
    !! CORA-style rating (inner corridor half the bounds' width; none
    !! without bounds: the rating's floor); no peaks.
    subroutine score_reference(rf, names, t0, dt, samples, sc, c, curves)
        type(reference_case_t), intent(in) :: rf !! the case's reference
        character(len=*), intent(in) :: names(:) !! channel names of the rows of samples
        real(wp), intent(in) :: t0               !! first sample time [s]
        real(wp), intent(in) :: dt               !! sample interval [s]
        real(wp), intent(in) :: samples(:, :)    !! (nchannel, nsample)
        type(score_t), intent(out) :: sc         !! the scores
        integer, intent(in) :: c                 !! the case's number (the curves' CSV)
        integer, intent(in), optional :: curves  !! unit of the curves' CSV
        real(wp) :: tm(size(samples, 2)), f(size(samples, 2)), g(size(samples, 2)), lag
        real(wp), allocatable :: y(:)
        integer :: m, i, stat
        character(len=msglen) :: msg
        do i = 1, size(tm)
            tm(i) = 1000*(t0 + (i - 1)*dt)
        end do
        m = size(rf%col)
        allocate (sc%rating(m), sc%corridor(m), sc%xcorr(m), sc%iso(m), sc%peak(0), sc%time(0), sc%z(0))
        do m = 1, size(rf%col)
            f = rf%scale(m)*samples(findloc(names, rf%channel(m), dim=1), :)
            if (len_trim(rf%minus(m)) > 0) f = f - rf%scale(m)*samples(findloc(names, rf%minus(m), dim=1), :)
            if (rf%from_start(m)) f = f - f(1)
            if (rf%cfc(m) > zero) then
                g = f
                call cfc_filter(g, dt, rf%cfc(m), f)
            end if
            associate (d => rf%data, k => rf%col(m))
                associate (tr => d%t(d%first(k):d%last(k)), r => d%mean(d%first(k):d%last(k), k))
                    y = resample(tr, tm, f)
                    call iso18571_rating(r, y, rated_interval(rf, m), sc%iso(m), stat, msg)
                    call cora_rating(tr, y, r, (d%upper(d%first(k):d%last(k), k) - d%lower(d%first(k):d%last(k), k))/2, &
                                     [tr(1), tr(size(tr))], sc%corridor(m), sc%xcorr(m), sc%rating(m), lag)
                    if (present(curves)) call write_curves(curves, c, rf%column(m), tr, r, y)
                end associate
            end associate
        end do
    end subroutine score_reference

    !> Score the peaks of a case of published peaks: each PEAK card's peak
    !! of the rated channels (filtered as the volunteers' are) on the run's
    !! own samples, z against the table's mean and SD where it gives the
    !! peak (0 elsewhere); no curve is rated.
    subroutine score_published(cal, c, names, t0, dt, samples, sc)
        type(calibration_t), intent(in) :: cal   !! the calibration
        integer, intent(in) :: c                 !! the case
        character(len=*), intent(in) :: names(:) !! channel names of the rows of samples
        real(wp), intent(in) :: t0               !! first sample time [s]
        real(wp), intent(in) :: dt               !! sample interval [s]
        real(wp), intent(in) :: samples(:, :)    !! (nchannel, nsample)
        type(score_t), intent(out) :: sc         !! the peaks, their times and z
        real(wp) :: tm(size(samples, 2)), y(size(samples, 2), size(cal%channels)), pk(2)
        integer :: i, p
        do i = 1, size(tm)
            tm(i) = 1000*(t0 + (i - 1)*dt)
        end do
        y = rated_histories(cal, tm, names, t0, dt, samples)
        allocate (sc%rating(0), sc%corridor(0), sc%xcorr(0), sc%iso(0), sc%peak(size(cal%peaks)), &
                  sc%time(size(cal%peaks)), sc%z(size(cal%peaks)))
        associate (pb => cal%pub(c))
            do p = 1, size(cal%peaks)
                pk = curve_peak(tm, y(:, cal%peaks(p)%curve), cal%peaks(p)%sign, cal%peaks(p)%window)
                sc%peak(p) = pk(1); sc%time(p) = pk(2)
                sc%z(p) = merge((pk(1) - pb%mean(p))/pb%sd(p), zero, pb%has(p))
            end do
        end associate
    end subroutine score_published

    !> Rows case,channel,time_ms,reference,model of one rated pair of curves.
    subroutine write_curves(u, c, name, t, r, y)
        integer, intent(in) :: u                 !! the CSV's unit
        integer, intent(in) :: c                 !! the case
        character(len=*), intent(in) :: name     !! the channel
        real(wp), intent(in) :: t(:), r(:), y(:) !! times [ms], reference, model
        integer :: i
        do i = 1, size(t)
            write (u, '(i0,a,a,3(a,es24.16e3))') c, ',', trim(name), ',', t(i), ',', r(i), ',', y(i)
        end do
    end subroutine write_curves

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

    !> Run the calibration: the VALUES point (when given) and the LHS starting points, then Nelder-Mead from
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
        real(wp) :: u0(size(cal%par)), ubest(size(u0)), j, jstart, lmax, lp, stx(size(cal%stand))
        type(score_t) :: sc(size(cal%sw))
        type(range_score_t) :: rg(size(cal%sw))
        logical :: ok
        integer :: r, k, nnm, cu, ios
        logical :: curves_open
        curves_open = .false.
        associate (par => cal%par)
            write (lu, '(a)') 'CALIBRATION: '//trim(cal%title)
            write (lu, '(a,i0,a,i0,a,i0)') 'cases ', size(cal%sw), ', parameters ', size(par), ', seed ', cal%seed
            call optional_report(cal, lu)
            if (cal%range_weight > zero) then
                write (lu, '(a,es10.3,a,es10.3,a,es10.3,a,es10.3,a,es10.3)') 'objective J = (1 - R) + W P + WT T '// &
                    '+ WR G; W ', cal%peak_weight, ', WT ', cal%time_weight, ', WR ', cal%range_weight, &
                    ', PEAK MARGIN M ', cal%peak_margin, ', RANGE MARGIN MR ', cal%range_inside
            else
                write (lu, '(a,es10.3,a,es10.3,a,es10.3)') 'objective J = (1 - R) + W P + WT T; W ', cal%peak_weight, &
                    ', WT ', cal%time_weight, ', PEAK MARGIN M ', cal%peak_margin
            end if
            write (lu, '(a)') 'R: '//trim(merge('MEAN ISO 18571 OVERALL RATING', 'MEAN CORA-STYLE RATING       ', &
                                                cal%metric == metric_iso18571))//' OF THE RATED CHANNELS'
            if (cal%max_evals == 0) then                 ! score the decks as they are, or at VALUES
                vbest = par%nominal
                if (size(cal%values) == size(par)) vbest = cal%values
                if (len_trim(cal%curves) > 0) then
                    open (newunit=cu, file=trim(cal%curves), status='replace', action='write', iostat=ios)
                    if (ios /= 0) then
                        write (lu, '(a)') 'CURVES FILE '//trim(cal%curves)//' CANNOT BE WRITTEN'
                    else
                        write (cu, '(a)') 'case,channel,time_ms,reference,model'
                        curves_open = .true.
                    end if
                end if
                if (curves_open) then
                    call evaluate(cal, vbest, jbest, sc, ok, lmax, lp, curves=cu, ranges=rg, standing=stx)
                    close (cu)
                else
                    call evaluate(cal, vbest, jbest, sc, ok, lmax, lp, ranges=rg, standing=stx)
                end if
                nevals = 1
                call score_report(cal, sc, rg, jbest, lu)
                call rest_report(lmax, lp, stx)
                return
            end if
            design = sweep_design(cal%sw(1))
            if (size(cal%values) == size(par)) design = reshape([cal%values, reshape(design, [size(design)])], &
                                                                [size(par), size(design, 2) + 1])
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
            call evaluate(cal, vbest, j, sc, ok, lmax, lp, ranges=rg, standing=stx)
            call score_report(cal, sc, rg, j, lu)
            call rest_report(lmax, lp, stx)
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
                v(i) = spread_value(cal%par(i), u(i))
                txt = field_text(v(i))
                if (cal%par(i)%kind == par_field) read (txt, *) v(i)
            end do
        end function values_of

        subroutine rest_report(lmax, lp, stx)
            real(wp), intent(in) :: lmax, lp, stx(:)
            integer :: k
            if (lmax > -huge(one)) write (lu, '(a,es10.3,a)') 'LARGEST REAL PART AT REST ', lmax, ' 1/S'// &
                trim(merge(' (NOT JUDGED: THE STANDING CASES ARE)', '                                     ', &
                           size(cal%stand) > 0))
            do k = 1, size(stx)
                if (stx(k) < huge(one)) then
                    write (lu, '(a,i0,a,es10.3,a,es10.3,a)') 'STANDING CASE ', k, ': LARGEST EXCURSION AT REST ', &
                        stx(k), ' DEG (BOUND ', cal%stand(k)%bound, ' DEG) '//trim(cal%stand(k)%deck)
                else
                    write (lu, '(a,i0,a)') 'STANDING CASE ', k, ': THE RUN AT REST DID NOT COMPLETE '// &
                        trim(cal%stand(k)%deck)
                end if
            end do
            if (cal%passive .and. lp < huge(one) .and. lp > -huge(one)) &
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

    !> One listing line per run of consecutive cases that leave out the same
    !! OPTIONAL parameters: 'cases 5-28 without (OPTIONAL, not in their decks): SIGMA ...'.
    subroutine optional_report(cal, lu)
        type(calibration_t), intent(in) :: cal   !! the calibration
        integer, intent(in) :: lu                !! listing unit
        character(len=:), allocatable :: label
        character(len=10), allocatable :: absent(:)
        integer :: k, r, i
        k = 1
        do while (k <= size(cal%sw))
            r = k
            do while (r < size(cal%sw))
                if (any(cal%sw(r + 1)%params%bound .neqv. cal%sw(k)%params%bound)) exit
                r = r + 1
            end do
            if (.not. all(cal%sw(k)%params%bound)) then
                label = trim(int_str(k))
                if (r > k) label = label//'-'//trim(int_str(r))
                absent = pack(cal%sw(k)%params%name, .not. cal%sw(k)%params%bound)
                write (lu, '(a,*(1x,a))') 'cases '//label//' without (OPTIONAL, not in their decks):', &
                    (trim(absent(i)), i=1, size(absent))
            end if
            k = r + 1
        end do
    end subroutine optional_report

    !> The ratings and peaks of every case, three significant digits; each
    !! channel's ISO 18571 scores (overall, corridor, phase, magnitude,
    !! slope) to six digits.
    subroutine score_report(cal, sc, rg, j, lu)
        type(calibration_t), intent(in) :: cal   !! the calibration
        type(score_t), intent(in) :: sc(:)       !! (case) the scores
        type(range_score_t), intent(in) :: rg(:) !! (case) the joints past their ranges
        real(wp), intent(in) :: j                !! the objective
        integer, intent(in) :: lu                !! listing unit
        integer :: c, k
        character(len=10) :: name
        write (lu, '(a,f8.4)') 'OBJECTIVE J = ', j
        do c = 1, size(sc)
            if (.not. (allocated(sc(c)%rating) .and. allocated(sc(c)%iso))) then
                write (lu, '(a,a,a)') 'CASE ', trim(cal%decks(c)), ': NOT RATED (A RUN FAILED, OR THE SET DOES '// &
                    'NOT PASS THE CHECKS AT REST)'
                cycle
            end if
            if (cal%pub(c)%on) then
                write (lu, '(a,a,a,f7.4,a)') 'CASE ', trim(cal%decks(c)), ' (WEIGHT', cal%weight(c), &
                    '): PUBLISHED PEAKS OF '//trim(cal%data(c))//' (NO CURVE RATED)'
                write (lu, '(2x,a,i0,a,f5.1,a,f5.1,a,f8.4)') 'RANGES: ', rg(c)%past, ' JOINT(S) PAST THEIR RANGE BY '// &
                    'MORE THAN ', range_margin/deg, ' DEG; LARGEST EXCESS ', rg(c)%largest/deg, ' DEG; G ', rg(c)%term
                call published_report(cal%pub(c), cal%peaks, sc(c), lu)
                cycle
            end if
            if (any(cal%weight /= one)) then
                write (lu, '(a,a,a,f7.4,a,f7.4)') 'CASE ', trim(cal%decks(c)), ' (WEIGHT', cal%weight(c), &
                    '): MEAN RATING ', case_rating(cal, sc(c))
            else
                write (lu, '(a,a,a,f7.4)') 'CASE ', trim(cal%decks(c)), ': MEAN RATING ', case_rating(cal, sc(c))
            end if
            do k = 1, size(sc(c)%rating)
                if (cal%ref(c)%on) then
                    name = cal%ref(c)%column(k)
                else
                    name = cal%channels(k)%name
                end if
                write (lu, '(2x,a10,a,f6.3,a,f6.3,a,f6.3)') name, ' RATING ', sc(c)%rating(k), &
                    '  C ', sc(c)%corridor(k), '  X ', sc(c)%xcorr(k)
                write (lu, '(2x,a10,a,f9.6,a,f9.6,a,f9.6,a,f9.6,a,f9.6)') name, ' ISO 18571 ', &
                    sc(c)%iso(k)%overall, '  CORRIDOR ', sc(c)%iso(k)%corridor, '  PHASE ', sc(c)%iso(k)%phase, &
                    '  MAGNITUDE ', sc(c)%iso(k)%magnitude, '  SLOPE ', sc(c)%iso(k)%slope
            end do
            write (lu, '(2x,a,i0,a,f5.1,a,f5.1,a,f8.4)') 'RANGES: ', rg(c)%past, ' JOINT(S) PAST THEIR RANGE BY MORE '// &
                'THAN ', range_margin/deg, ' DEG; LARGEST EXCESS ', rg(c)%largest/deg, ' DEG; G ', rg(c)%term
            if (cal%ref(c)%on) cycle
            do k = 1, size(cal%peaks)
                write (lu, '(2x,a16,a,es10.3,a,f6.1,a,es10.3,a,es9.2,a,f6.1,a,f5.1,a,f6.2)') cal%peaks(k)%name, &
                    ' MODEL ', sc(c)%peak(k), ' AT ', sc(c)%time(k), ' MS; VOLUNTEERS ', cal%vol(c)%peak_mean(k), &
                    ' +- ', cal%vol(c)%peak_sd(k), ' AT ', cal%vol(c)%time_mean(k), ' +- ', cal%vol(c)%time_sd(k), &
                    '; Z ', sc(c)%z(k)
            end do
        end do
    end subroutine score_report

    !> The peaks of a case of published peaks that its table gives: the
    !! model's, the published mean and SD (and time), z.
    subroutine published_report(pb, peaks, sc, lu)
        type(peak_table_t), intent(in) :: pb     !! the table
        type(peak_t), intent(in) :: peaks(:)     !! the PEAK cards
        type(score_t), intent(in) :: sc          !! the case's scores
        integer, intent(in) :: lu                !! listing unit
        integer :: k
        do k = 1, size(peaks)
            if (.not. pb%has(k)) cycle
            if (pb%has_time(k)) then
                write (lu, '(2x,a16,a,es10.3,a,f6.1,a,es10.3,a,es9.2,a,f6.1,a,f5.1,a,f6.2)') peaks(k)%name, &
                    ' MODEL ', sc%peak(k), ' AT ', sc%time(k), ' MS; PUBLISHED ', pb%mean(k), ' +- ', pb%sd(k), &
                    ' AT ', pb%time_mean(k), ' +- ', pb%time_sd(k), '; Z ', sc%z(k)
            else
                write (lu, '(2x,a16,a,es10.3,a,f6.1,a,es10.3,a,es9.2,a,f6.2)') peaks(k)%name, ' MODEL ', &
                    sc%peak(k), ' AT ', sc%time(k), ' MS; PUBLISHED ', pb%mean(k), ' +- ', pb%sd(k), '; Z ', sc%z(k)
            end if
        end do
    end subroutine published_report

    !> Run every volunteer case of the calibration at parameter values v:
    !! the rated channels at the volunteers' times, y(:, :, case) (zero for
    !! a reference case); ok false when a run fails.
    subroutine member_histories(cal, v, y, ok)
        type(calibration_t), intent(in) :: cal   !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp), intent(out) :: y(:, :, :)          !! (nt, nchannel, ncase)
        logical, intent(out) :: ok               !! every run complete
        type(case_t) :: cs
        type(run_result_t) :: res
        type(channel_set_t) :: ch
        integer :: c
        ok = .true.
        y = zero
        do c = 1, size(cal%sw)
            if (cal%ref(c)%on .or. cal%pub(c)%on) cycle
            call run_member(cal, c, v, cs, ch, res, ok)
            if (.not. ok) return
            y(1:size(cal%vol(c)%t), :, c) = rated_histories(cal, cal%vol(c)%t, ch%name, cs%t_start, cs%sample_dt, &
                                                             res%samples)
        end do
    end subroutine member_histories

    !> Run case c at parameter values v as a sweep member: no result file,
    !! the listing to /dev/null (its header only: no tables, peaks or
    !! criteria), only the rated channels computed, their samples kept in res.
    subroutine run_member(cal, c, v, cs, ch, res, ok)
        type(calibration_t), intent(in) :: cal   !! the calibration
        integer, intent(in) :: c                 !! the case
        real(wp), intent(in) :: v(:)             !! one value per parameter
        type(case_t), intent(out) :: cs          !! the member's case
        type(channel_set_t), intent(out) :: ch   !! its channels
        type(run_result_t), intent(out) :: res   !! its run, with the samples
        logical, intent(out) :: ok               !! the run is complete
        integer :: stat, lu
        character(len=msglen) :: msg
        character(len=chname_len), allocatable :: rated(:)
        ok = .false.
        call sweep_member_case(cal%sw(c), v, cs, stat, msg, deck_sampling=cal%ref(c)%on)
        if (stat /= stat_ok) return
        ! the rated channels alone: the CHANNEL cards' or the RATED cards' (and what they subtract)
        if (cal%ref(c)%on) then
            rated = [character(len=chname_len) :: cal%ref(c)%channel, &
                     pack(cal%ref(c)%minus, len_trim(cal%ref(c)%minus) > 0)]
        else
            rated = [character(len=chname_len) :: cal%channels%name]
        end if
        open (newunit=lu, file='/dev/null', action='write')
        block
            type(run_state_t) :: run         ! a fresh run object for every case
            call run%execute(cs, lu, '', res, keep_samples=.true., only=rated)
        end block
        close (lu)
        if (res%exit_code /= exit_ok) return
        call channels_define(cs, ch, rated)
        ok = .true.
    end subroutine run_member

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
