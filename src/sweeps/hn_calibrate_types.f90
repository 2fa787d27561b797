!> The data of a calibration (hn_calibrate): its cases (deck, volunteers,
!! reference or published peaks, weight, the sweep binding the parameters
!! to the deck), its study (rated channels, peaks, window, filter,
!! metric), the optimizer's settings, and the state of the reading of a
!! calibration deck from card to card (hn_calibrate_deck,
!! hn_calibrate_case_cards, hn_calibrate_cases).
module hn_calibrate_types
    use hn_kinds, only: wp, zero
    use hn_case, only: deck_line_t, path_len
    use hn_card_engine, only: card_deck_t
    use hn_sweep, only: sweep_t, sweep_param_t
    use hn_rating, only: peak_t, corridor_t
    use hn_volunteer_data, only: data_channel_t, reference_data_t, peak_table_t
    implicit none
    private

    integer, parameter, public :: metric_cora = 1, metric_iso18571 = 2   !! RATING F5

    !> The rated channels of a reference case (DATA a reference CSV): its
    !! curves and, per rated channel (RATED card, or each column of the
    !! CSV under its own name), the model curve compared with it:
    !! scale (channel - minus), less its value at the start with START,
    !! filtered by its CFC class when one is given.
    type, public :: reference_case_t
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
    !! of its run moves more than the bound from its start (REST: the head's
    !! rotation at any time of the run; RETURN: at its end).
    type, public :: standing_case_t
        character(len=path_len) :: deck = ''   !! the deck (STANDING columns 11-70)
        real(wp) :: bound = zero               !! the largest excursion allowed (STANDING F7) [deg]
        character(len=8) :: kind = 'STANDING'  !! its card: STANDING (joints), RETURN (head at the end), REST (head throughout)
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
    type, public :: calibration_t
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
    !! deck itself (`rd`, of the card engine's card_deck_t) and where each
    !! card was, for the checks across cards and the located messages of
    !! each case's binding to its sweep.
    type, extends(card_deck_t), public :: calibration_deck_t
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
        integer :: rating_line = 0                       !! the line of the RATING card (0: none yet)
        integer :: values_line = 0                       !! the line of the first VALUES card (0: none)
    end type calibration_deck_t

    !> A calibration deck being read by the card engine (its handlers in
    !! hn_calibrate_deck and hn_calibrate_case_cards): what is kept from card
    !! to card and the calibration the cards fill.
    type, extends(calibration_deck_t), public :: calibration_reading_t
        type(calibration_t) :: cal                       !! the calibration, its cases not yet bound
    end type calibration_reading_t


end module hn_calibrate_types
