!> Parameter sweeps: the sweep deck (a base case deck, the parameters to
!! vary and a design of experiments), the design itself (full factorial,
!! Latin hypercube, one-at-a-time), the case of each member and its run
!! with the summary outputs a sensitivity study needs. Nothing here knows
!! about MPI: a driver hands out member numbers (serially, or over ranks)
!! and collects `member_record_t`s. The deck format is in docs/sweeps.md.
module hn_sweep
    use hn_kinds, only: wp, zero, one, msglen, deg
    use hn_case, only: case_t, deck_line_t, path_len
    use hn_deck_reader, only: deck_reader_t, read_card_images, field_columns, int_str, nfields, upper, field_text, &
                              field_value, locate_field, stdin_path
    use hn_card_engine, only: card_deck_t, deck_format_t, deck_card_t, read_deck_cards, any_times, exactly_once
    use hn_deck, only: read_case_lines
    use hn_changes, only: read_param_kind, kind_family, kind_body, kind_field
    use hn_tree, only: tree_build
    use hn_model, only: model_set_neutral, family_count, family_items, family_items_text, scale_family
    use hn_families, only: family_index, family_names_text
    use hn_run, only: run_state_t, run_result_t, exit_deck, exit_ok
    use hn_channels, only: channel_set_t, channels_define
    use hn_filters, only: cfc_filter
    use hn_optimize, only: latin_hypercube
    use hn_head_angles, only: bryant_angles, bryant_angles_near, rotation_angle, signed_extreme, extreme_index
    use hn_whiplash, only: contact_onset
    implicit none
    private

    public :: sweep_t, sweep_param_t, param_tie_t, member_record_t, read_sweep, read_sweep_lines, sweep_design, &
              sweep_member_case, spread_value, &
              run_member, field_text, param_target_text
    public :: output_names, output_units, output_ref, output_group, nout, name_len, member_summary

    integer, parameter, public :: par_family = kind_family, par_body = kind_body, par_field = kind_field
    integer, parameter, public :: design_factorial = 1, design_lhs = 2, design_oat = 3
    character(len=9), parameter, public :: design_name(3) = [character(len=9) :: 'FACTORIAL', 'LHS', 'OAT']
    integer, parameter :: max_params = 50, max_runs = 100000
    character(len=1), parameter :: xyz(3) = ['X', 'Y', 'Z']

    !> The summary outputs of a member run: the sagittal set (1-13, in the
    !! order of the first sweeps), the 3-D set (14-28) and the rear-impact
    !! set (29-31); docs/sweeps.md.
    integer, parameter :: nout = 31
    integer, parameter :: name_len = 12   !! longest output name
    character(len=name_len), parameter :: output_names(nout) = [character(len=name_len) :: 'THETA_PEAK', &
        'THETA_TIME', 'OMEGA_PEAK', 'ALPHA_PEAK', 'HEAD_AR', 'OC_TENSION', 'OC_COMPR', 'OC_SHEAR', 'OC_FLEX', &
        'OC_EXT', 'HIC15', 'NIJ', 'NIC', &
        'HEAD_RX_PEAK', 'HEAD_RY_PEAK', 'HEAD_RZ_PEAK', 'HEAD_ANGLE', 'HEAD_ANGLE_T', 'OMEGA_X_PEAK', &
        'OMEGA_Z_PEAK', 'OMEGA_RES', 'ALPHA_RES', 'OC_FX_PEAK', 'OC_FY_PEAK', 'OC_SHEAR_RES', 'OC_MX_PEAK', &
        'OC_MZ_PEAK', 'OC_M_RES', 'HT1_EXT', 'HT1_EXT_T', 'CONTACT_T']
    character(len=8), parameter :: output_units(nout) = [character(len=8) :: 'deg', 'ms', 'rad/s', 'rad/s^2', &
        'g', 'N', 'N', 'N', 'N m', 'N m', '-', '-', 'm^2/s^2', &
        'deg', 'deg', 'deg', 'deg', 'ms', 'rad/s', 'rad/s', 'rad/s', 'rad/s^2', 'N', 'N', 'N', 'N m', 'N m', 'N m', &
        'deg', 'ms', 'ms']
    !> The output whose magnitude tells whether output k is only roundoff:
    !! itself, or for a time the extreme it is the time of.
    integer, parameter :: output_ref(nout) = [1, 1, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, &
        14, 15, 16, 17, 17, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 29, 31]
    !> Outputs of one quantity and unit share a group; an output is roundoff
    !! when it is far below the largest output of its group (angles,
    !! angular velocities, angular accelerations, head acceleration, neck
    !! forces, neck moments, HIC15, Nij, NIC; times take their extreme's;
    !! the contact time is its own).
    integer, parameter :: output_group(nout) = [1, 0, 2, 3, 4, 5, 5, 5, 6, 6, 7, 8, 9, &
        1, 1, 1, 1, 0, 2, 2, 2, 3, 5, 5, 5, 6, 6, 6, 1, 0, 0]

    !> A further deck field a FIELD parameter writes (a second PARAM card of
    !! its name): the value a + b x, x the parameter's value.
    type :: param_tie_t
        character(len=10) :: target = ''   !! card name
        character(len=10) :: item = ''     !! the name in field F1 of the card (name.text: F2 or F3 holds text)
        integer :: field = 0               !! field number across the card
        integer :: line = 0                !! base deck line holding the field
        integer :: card_line = 0           !! sweep deck line of the PARAM card
        real(wp) :: a = zero, b = one      !! the map from the parameter's value
    end type param_tie_t

    !> One parameter of the sweep.
    type :: sweep_param_t
        character(len=10) :: name = ''
        integer :: kind = par_family
        character(len=10) :: target = ''   !! family, body or card name
        character(len=10) :: item = ''     !! property, or the name in field F1 of the card
        integer :: field = 0               !! field number across the card (FIELD kinds)
        real(wp) :: low = zero, high = zero
        logical :: log_spacing = .false.
        real(wp) :: nominal = one          !! scale 1, or the base deck's field value
        integer :: family = 0              !! family number (FAMILY kind)
        integer :: body = 0                !! body number (BODY kind)
        integer :: line = 0                !! base deck line holding the field (FIELD kind)
        integer :: card_line = 0           !! sweep deck line of the PARAM card
        logical :: if_present = .false.    !! bound only where the base deck has the target (a calibration's OPTIONAL)
        logical :: bound = .true.          !! bound in this base deck (false: if_present and the target absent)
        type(param_tie_t), allocatable :: ties(:)  !! further fields it writes (FIELD kind)
    end type sweep_param_t

    !> A sweep: base deck, parameters, design.
    type :: sweep_t
        character(len=80) :: title = ''
        character(len=path_len) :: base = ''      !! base deck path as the BASE card gives it
        character(len=path_len) :: base_path = '' !! where it was found (as an INCLUDE file is)
        character(len=path_len), allocatable :: search(:)  !! include path of the base deck and its data files
        character(len=path_len) :: h5file = ''    !! result file named in the sweep deck
        type(deck_line_t), allocatable :: base_lines(:)
        integer :: design = design_oat
        integer :: levels = 0                     !! FACTORIAL
        integer :: nlhs = 0, seed = 0             !! LHS
        real(wp) :: percent = zero                !! OAT
        type(sweep_param_t), allocatable :: params(:)
        type(deck_line_t), allocatable :: deck(:) !! the sweep deck as read
    end type sweep_t

    !> What one member run gave.
    type :: member_record_t
        integer :: status = -1                  !! exit code of the member (0 complete), -1 not run
        character(len=msglen) :: message = ''   !! why it failed, or its warning
        real(wp) :: outputs(nout) = zero        !! summary outputs (zero when it failed)
        real(wp) :: t_reached = zero
        real(wp) :: wall = zero
        integer :: nevals = 0
        integer :: rank = 0                     !! MPI rank that ran it
    end type member_record_t

    !> A sweep deck being read by the card engine: the sweep its cards fill
    !! and the file it came from (its BASE deck is looked for next to it).
    type, extends(card_deck_t) :: sweep_deck_t
        type(sweep_t) :: sw                       !! the sweep the cards fill
        character(len=:), allocatable :: path     !! the sweep deck's file (stdin_path: none)
    end type sweep_deck_t

contains

    !> Read the sweep deck `path` (named `source` in messages), the base
    !! deck it names, and check every parameter against the base deck. The
    !! base deck and the INCLUDE files of both decks are looked for as a
    !! single run looks for INCLUDE files: next to the including file, in
    !! the working directory, then in `include_path` (-I, HHNECK_PATH).
    subroutine read_sweep(path, source, sw, stat, errmsg, include_path)
        character(len=*), intent(in) :: path           !! sweep deck file, or stdin_path
        character(len=*), intent(in) :: source         !! its name in messages
        type(sweep_t), intent(out) :: sw               !! the sweep (base deck lines, parameters, design)
        integer, intent(out) :: stat                   !! stat_ok, or stat_bad_input (the first error)
        character(len=msglen), intent(out) :: errmsg   !! the first error, located in the sweep or base deck
        character(len=*), intent(in), optional :: include_path(:)  !! directories searched for INCLUDE and BASE files
        type(sweep_deck_t) :: dk
        dk%rd%top = source
        allocate (dk%rd%search(0))
        if (present(include_path)) dk%rd%search = include_path
        call read_card_images(dk%rd, path, source, 0)
        if (.not. dk%rd%failed() .and. dk%rd%nlines == 0) &
            call dk%rd%fail(source//' line 1: the sweep deck is empty; expected a TITLE card first')
        dk%path = path
        call parse_sweep(dk, source, [character(len=10) ::])
        sw = dk%sw
        stat = dk%rd%stat
        errmsg = dk%rd%errmsg
    end subroutine read_sweep

    !> A sweep deck already read into card images (INCLUDE expanded), e.g.
    !! one assembled in memory by the calibration for each of its cases.
    !! Its BASE deck is looked for as in read_sweep, next to `path` when given.
    !! A parameter named in `optional_names` whose target the base deck lacks
    !! is left unbound (the caller checks that some case binds it).
    subroutine read_sweep_lines(lines, source, sw, stat, errmsg, include_path, path, optional_names)
        type(deck_line_t), intent(in) :: lines(:)      !! card images
        character(len=*), intent(in) :: source         !! name of the deck in messages
        type(sweep_t), intent(out) :: sw               !! the sweep (base deck lines, parameters, design)
        integer, intent(out) :: stat                   !! stat_ok, or stat_bad_input (the first error)
        character(len=msglen), intent(out) :: errmsg   !! the first error, located in the sweep or base deck
        character(len=*), intent(in), optional :: include_path(:)  !! directories searched for INCLUDE and BASE files
        character(len=*), intent(in), optional :: path !! the file the lines came from (absent: none, as stdin)
        character(len=*), intent(in), optional :: optional_names(:)  !! parameters bound only where their target is
        type(sweep_deck_t) :: dk
        character(len=10), allocatable :: opt(:)
        dk%rd%top = source
        dk%rd%lines = lines
        dk%rd%nlines = size(lines)
        allocate (dk%rd%search(0))
        if (present(include_path)) dk%rd%search = include_path
        allocate (opt(0))
        if (present(optional_names)) opt = optional_names
        dk%path = stdin_path
        if (present(path)) dk%path = path
        call parse_sweep(dk, source, opt)
        sw = dk%sw
        stat = dk%rd%stat
        errmsg = dk%rd%errmsg
    end subroutine read_sweep_lines

    !> The sweep deck's cards for the card engine (docs/sweeps.md).
    function sweep_format() result(fmt)
        type(deck_format_t) :: fmt
        fmt%name = 'sweep'
        fmt%doc = 'docs/sweeps.md'
        allocate (fmt%cards, source=[deck_card_t('TITLE', 0, any_times, title_card), &
                                     deck_card_t('BASE', 0, exactly_once, base_card), &
                                     deck_card_t('DESIGN', 0, exactly_once, design_card), &
                                     deck_card_t('PARAM', 0, any_times, param_card), &
                                     deck_card_t('H5FILE', 0, any_times, h5file_card)])
    end function sweep_format

    !> The cards of a sweep deck (the card engine), the base deck they name,
    !! and every parameter checked against the base deck.
    subroutine parse_sweep(dk, source, optional_names)
        type(sweep_deck_t), intent(inout) :: dk
        character(len=*), intent(in) :: source
        character(len=*), intent(in) :: optional_names(:)  ! parameters left unbound where their target is absent
        type(case_t) :: base
        character(len=msglen) :: errmsg
        integer :: p, stat
        allocate (dk%sw%params(0))
        dk%sw%search = dk%rd%search
        call read_deck_cards(dk, sweep_format())
        associate (rd => dk%rd, sw => dk%sw)
            if (size(sw%params) == 0 .and. .not. rd%failed()) &
                call rd%fail(source//': found no PARAM card; expected 1 to '//trim(int_str(max_params)))
            if (.not. rd%failed()) sw%deck = rd%lines(1:rd%nlines)
            ! the base deck as it is, then every parameter against it
            if (.not. rd%failed()) then
                call read_case_lines(sw%base_lines, trim(sw%base), base, stat, errmsg, sw%search)
                if (stat /= 0) call rd%fail('base deck '//trim(sw%base)//': '//trim(errmsg))
            end if
            if (.not. rd%failed()) then
                do p = 1, size(sw%params)
                    sw%params(p)%if_present = any(optional_names == sw%params(p)%name)
                    call bind_param(rd, sw, base, sw%params(p))
                    if (rd%failed()) exit
                end do
            end if
            if (.not. rd%failed()) then
                if (design_runs(sw) > max_runs) call rd%fail(source//': the design has '// &
                    trim(int_str(design_runs(sw)))//' runs; at most '//trim(int_str(max_runs))//' are allowed')
            end if
            if (.not. rd%failed()) call check_extremes(rd, sw)
        end associate
    end subroutine parse_sweep

    !> The TITLE card: the sweep's title (columns 11-80).
    subroutine title_card(deck, i)
        class(card_deck_t), intent(inout) :: deck   !! the sweep deck (sweep_deck_t)
        integer, intent(in) :: i                    !! the card's deck line
        select type (dk => deck)
        type is (sweep_deck_t)
            dk%sw%title = adjustl(dk%rd%lines(i)%text(11:80))
        end select
    end subroutine title_card

    !> The H5FILE card: the sweep's result file (columns 11-80).
    subroutine h5file_card(deck, i)
        class(card_deck_t), intent(inout) :: deck   !! the sweep deck (sweep_deck_t)
        integer, intent(in) :: i                    !! the card's deck line
        select type (dk => deck)
        type is (sweep_deck_t)
            dk%sw%h5file = adjustl(dk%rd%lines(i)%text(11:80))
        end select
    end subroutine h5file_card

    !> The BASE card: the base case deck (columns 11-80), found as an INCLUDE file is
    !! (next to the file holding the card, here, the include path), and read.
    subroutine base_card(deck, i)
        class(card_deck_t), intent(inout) :: deck   !! the sweep deck (sweep_deck_t)
        integer, intent(in) :: i                    !! the card's deck line
        type(deck_reader_t) :: bd
        character(len=msglen) :: errmsg
        character(len=:), allocatable :: found
        select type (dk => deck)
        type is (sweep_deck_t)
            associate (rd => dk%rd, sw => dk%sw)
                sw%base = adjustl(rd%lines(i)%text(11:80))
                if (len_trim(sw%base) == 0) then
                    call rd%fail(rd%where(i)//', columns 11-80 (BASE card): found no file name; expected the '// &
                                 'path of the base case deck')
                    return
                end if
                if (rd%lines(i)%via > 0) then
                    call rd%find_file(trim(sw%base), rd%lines(i)%source, found, errmsg)
                else
                    call rd%find_file(trim(sw%base), dk%path, found, errmsg)
                end if
                if (len(found) == 0) then
                    call rd%fail(rd%where(i)//', columns 11-80 (BASE card): '//trim(errmsg))
                    return
                end if
                sw%base_path = found
                bd%top = found
                bd%search = rd%search
                call read_card_images(bd, found, found, 0)
                if (bd%failed()) then
                    call rd%fail('base deck named at '//rd%where(i)//': '//trim(bd%errmsg))
                else
                    sw%base_lines = bd%lines(1:bd%nlines)
                end if
            end associate
        end select
    end subroutine base_card

    !> The DESIGN card: FACTORIAL levels, LHS runs and seed, or OAT step (%).
    subroutine design_card(deck, i)
        class(card_deck_t), intent(inout) :: deck   !! the sweep deck (sweep_deck_t)
        integer, intent(in) :: i                    !! the card's deck line
        character(len=10) :: s
        select type (dk => deck)
        type is (sweep_deck_t)
            associate (rd => dk%rd, sw => dk%sw)
                call rd%name(i, 1, 'design', s)
                select case (s)
                case ('FACTORIAL')
                    sw%design = design_factorial
                    call rd%int(i, 2, 'levels per parameter', sw%levels, 2, 20)
                case ('LHS')
                    sw%design = design_lhs
                    call rd%int(i, 2, 'number of runs', sw%nlhs, 2, max_runs)
                    call rd%int(i, 3, 'seed', sw%seed, 1, 2147483646)
                case ('OAT')
                    sw%design = design_oat
                    call rd%real(i, 2, 'step', '%', sw%percent, 1.0e-3_wp, 99.0_wp)
                case default
                    if (.not. rd%failed()) call rd%fail(rd%context(i, 1, 'design')//': found "'//trim(s)// &
                                                        '"; expected FACTORIAL, LHS or OAT')
                end select
            end associate
        end select
    end subroutine design_card

    !> One PARAM card: name, kind, target, item, low, high, spacing; a
    !! second card of a FIELDn parameter's name is a further field it writes.
    subroutine param_card(deck, i)
        class(card_deck_t), intent(inout) :: deck   !! the sweep deck (sweep_deck_t)
        integer, intent(in) :: i                    !! the card's deck line
        select type (dk => deck)
        type is (sweep_deck_t)
            call read_param(dk%rd, i, dk%sw)
        end select
    end subroutine param_card

    !> The fields of a PARAM card into the sweep's parameters.
    subroutine read_param(rd, i, sw)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i
        type(sweep_t), intent(inout) :: sw
        type(sweep_param_t) :: p
        character(len=10) :: s
        integer :: k
        if (size(sw%params) >= max_params) then
            call rd%fail(rd%where(i)//' (PARAM card): more than '//trim(int_str(max_params))//' parameters')
            return
        end if
        p%card_line = i
        allocate (p%ties(0))
        call rd%name(i, 1, 'parameter name', p%name)
        k = findloc(sw%params%name, p%name, dim=1)
        if (k > 0 .and. .not. rd%failed()) then
            call tie_card(rd, i, sw%params(k))
            return
        end if
        call read_param_kind(rd, i, 2, p%kind, p%field)
        if (rd%failed()) return
        call rd%name(i, 3, 'target', p%target)
        call rd%name(i, 4, 'item', p%item, optional_blank=p%kind == par_field)
        if (sw%design == design_oat .and. rd%is_blank(i, 5) .and. rd%is_blank(i, 6)) then
            p%low = zero; p%high = zero
        else
            call rd%real(i, 5, 'low', '-', p%low, -1.0e30_wp, 1.0e30_wp)
            call rd%real(i, 6, 'high', '-', p%high, -1.0e30_wp, 1.0e30_wp)
            if (.not. rd%failed() .and. .not. p%high > p%low) &
                call rd%fail(rd%context(i, 6, 'high')//': found a high value not above the low value '// &
                             trim(rd%raw(i, 5))//'; expected high > low')
        end if
        call rd%name(i, 7, 'spacing', s, optional_blank=.true.)
        if (.not. rd%failed()) then
            if (s == 'LOG') then
                p%log_spacing = .true.
            else if (s /= 'LIN' .and. s /= '') then
                call rd%fail(rd%context(i, 7, 'spacing')//': found "'//trim(s)//'"; expected LIN, LOG or blank')
            end if
        end if
        if (.not. rd%failed() .and. p%log_spacing .and. p%low <= zero .and. p%high > zero) &
            call rd%fail(rd%context(i, 5, 'low')//': found '//trim(rd%raw(i, 5))// &
                         '; expected a positive value for LOG spacing')
        if (.not. rd%failed() .and. p%kind /= par_field .and. p%high > zero .and. p%low <= zero) &
            call rd%fail(rd%context(i, 5, 'low')//': found '//trim(rd%raw(i, 5))// &
                         '; expected a positive scale factor (FAMILY and BODY parameters scale the base values)')
        if (.not. rd%failed()) sw%params = [sw%params, p]
    end subroutine read_param

    !> A second PARAM card of a FIELDn parameter's name: a further field the
    !! parameter writes, F5 and F6 the values written there when the
    !! parameter is at its low and high value (a linear map), F7 blank.
    subroutine tie_card(rd, i, p)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i
        type(sweep_param_t), intent(inout) :: p
        type(param_tie_t) :: t
        real(wp) :: low, high
        integer :: kind
        t%card_line = i
        call read_param_kind(rd, i, 2, kind, t%field)
        if (rd%failed()) return
        if (kind /= par_field .or. p%kind /= par_field .or. .not. p%high > p%low) then
            call rd%fail(rd%context(i, 1, 'parameter name')//': found "'//trim(p%name)// &
                         '" a second time; expected a new name (only a FIELDn parameter with a range is named '// &
                         'again, by FIELDn cards: further fields it writes)')
            return
        end if
        call rd%name(i, 3, 'target', t%target)
        call rd%name(i, 4, 'item', t%item, optional_blank=.true.)
        call rd%real(i, 5, 'low', '-', low, -1.0e30_wp, 1.0e30_wp)
        call rd%real(i, 6, 'high', '-', high, -1.0e30_wp, 1.0e30_wp)
        if (.not. rd%failed() .and. .not. rd%is_blank(i, 7)) &
            call rd%fail(rd%context(i, 7, 'spacing')//': found "'//trim(rd%raw(i, 7))//'"; expected blank (the '// &
                         'field follows the parameter '//trim(p%name)//' linearly)')
        if (rd%failed()) return
        t%b = (high - low)/(p%high - p%low)
        t%a = low - t%b*p%low
        p%ties = [p%ties, t]
    end subroutine tie_card

    !> Resolve a parameter against the base case: family and property, body,
    !! or the deck line and field (and those of its ties), and its nominal value.
    subroutine bind_param(rd, sw, base, p)
        type(deck_reader_t), intent(inout) :: rd
        type(sweep_t), intent(in) :: sw
        type(case_t), intent(in) :: base
        type(sweep_param_t), intent(inout) :: p
        character(len=:), allocatable :: at
        real(wp) :: x
        integer :: k
        at = rd%where(p%card_line)//' (PARAM '//trim(p%name)//')'
        select case (p%kind)
        case (par_family)
            p%family = family_index(p%target)
            if (p%family == 0) then
                call rd%fail(rd%context(p%card_line, 3, 'target')//': found "'//trim(p%target)// &
                             '"; expected '//family_names_text())
                return
            end if
            if (.not. any(family_items(p%family) == p%item)) then
                call rd%fail(rd%context(p%card_line, 4, 'item')//': found "'//trim(p%item)//'"; expected '// &
                             family_items_text(p%family)//' for '//trim(p%target))
                return
            end if
            if (family_count(base%model, p%family) == 0) then
                p%bound = .not. p%if_present
                if (p%bound) call rd%fail(at//': the base deck has no '//trim(p%target)//'; nothing to vary')
            end if
        case (par_body)
            p%body = findloc(base%model%tree%name, p%target, dim=1)
            if (p%body == 0 .and. p%if_present) then
                p%bound = .false.
            else if (p%body == 0) then
                call rd%fail(rd%context(p%card_line, 3, 'target')//': found "'//trim(p%target)// &
                             '"; expected a body of the base deck (after its MERGE cards)')
                return
            end if
            if (p%item /= 'MASS' .and. p%item /= 'INERTIA') &
                call rd%fail(rd%context(p%card_line, 4, 'item')//': found "'//trim(p%item)// &
                             '"; expected MASS or INERTIA')
        case (par_field)
            call bind_field(rd, sw, at, p%target, p%item, p%field, p%if_present, p%line, p%nominal, p%bound)
            do k = 1, size(p%ties)
                if (rd%failed() .or. .not. p%bound) exit
                call bind_field(rd, sw, rd%where(p%ties(k)%card_line)//' (PARAM '//trim(p%name)//')', &
                                p%ties(k)%target, p%ties(k)%item, p%ties(k)%field, .false., p%ties(k)%line, x, p%bound)
            end do
        end select
        if (rd%failed()) return
        if (sw%design == design_oat) then
            if (p%nominal == zero) call rd%fail(at//': the nominal value is 0; a one-at-a-time step of '// &
                                                 'a percentage needs a nonzero nominal value')
            if (p%log_spacing .and. p%nominal < zero) call rd%fail(at//': LOG spacing needs a positive nominal')
        end if
    end subroutine bind_param

    !> The base deck line of field `field` of the card `target` named `item`
    !! (F1; `name.text` when no card's F1 is the whole item: the card whose
    !! F1 is name and whose F2 or F3 is text) and the number it holds.
    subroutine bind_field(rd, sw, at, target, item, field, if_present, line, nominal, bound)
        type(deck_reader_t), intent(inout) :: rd
        type(sweep_t), intent(in) :: sw
        character(len=*), intent(in) :: at, target, item
        integer, intent(in) :: field
        logical, intent(in) :: if_present
        integer, intent(out) :: line
        real(wp), intent(out) :: nominal
        logical, intent(inout) :: bound
        integer :: nfound, c1, c2, ios, k
        nominal = zero
        call locate_field(sw%base_lines, target, item, field, nfound, line, c1, c2)
        k = index(item, '.', back=.true.)
        if (nfound == 0 .and. k > 1 .and. k < len_trim(item)) &
            call locate_field(sw%base_lines, target, item(:k - 1), field, nfound, line, c1, c2, name23=item(k + 1:))
        if (nfound == 0 .and. if_present) then
            bound = .false.
            return
        else if (nfound /= 1) then
            call rd%fail(at//': found '//trim(int_str(nfound))//' '//trim(target)//' cards'// &
                         trim(merge(' named '//item, repeat(' ', 17), len_trim(item) > 0))// &
                         ' in the base deck; expected exactly one (item name.text: the card named name whose '// &
                         'F2 or F3 holds text)')
            return
        end if
        if (line == 0) then
            call rd%fail(at//': the '//trim(target)//' card has no continuation card for field '// &
                         trim(int_str(field)))
            return
        end if
        read (sw%base_lines(line)%text(c1:c2), *, iostat=ios) nominal
        if (ios /= 0 .or. len_trim(sw%base_lines(line)%text(c1:c2)) == 0) &
            call rd%fail(at//': '//sw%base_lines(line)%source//' line '// &
                         trim(int_str(sw%base_lines(line)%line))//', columns '//trim(int_str(c1))//'-'// &
                         trim(int_str(c2))//' holds "'//trim(sw%base_lines(line)%text(c1:c2))// &
                         '"; expected a number to vary')
    end subroutine bind_field

    !> What a parameter's target is, in words: 'MUSCLES', 'body HEAD',
    !! 'SCALE card named SIGMA'.
    pure function param_target_text(p) result(t)
        type(sweep_param_t), intent(in) :: p   !! the parameter
        character(len=:), allocatable :: t
        select case (p%kind)
        case (par_family)
            t = trim(p%target)
        case (par_body)
            t = 'body '//trim(p%target)
        case default
            t = trim(p%target)//' card'//trim(merge(' named '//p%item, repeat(' ', 17), len_trim(p%item) > 0))
        end select
    end function param_target_text

    !> Every parameter at its low and high value (OAT: its two steps), the
    !! others nominal: the base deck must accept them.
    subroutine check_extremes(rd, sw)
        type(deck_reader_t), intent(inout) :: rd
        type(sweep_t), intent(in) :: sw
        type(case_t) :: cs
        real(wp) :: v(size(sw%params)), ends(2)
        integer :: p, e, stat
        character(len=msglen) :: msg
        do p = 1, size(sw%params)
            if (sw%params(p)%kind /= par_field .or. .not. sw%params(p)%bound) cycle
            ends = [sw%params(p)%low, sw%params(p)%high]
            if (sw%design == design_oat) ends = oat_values(sw, p)
            do e = 1, 2
                v = sw%params%nominal
                v(p) = ends(e)
                call sweep_member_case(sw, v, cs, stat, msg)
                if (stat /= 0) then
                    call rd%fail(rd%where(sw%params(p)%card_line)//' (PARAM '//trim(sw%params(p)%name)// &
                                 '): the value '//trim(field_text(ends(e)))//' is refused by the base deck: '// &
                                 trim(msg))
                    return
                end if
            end do
        end do
    end subroutine check_extremes

    !> Number of member runs of the design.
    pure integer function design_runs(sw) result(n)
        type(sweep_t), intent(in) :: sw
        real(wp) :: big
        select case (sw%design)
        case (design_factorial)
            big = real(sw%levels, wp)**size(sw%params)
            n = int(min(big, real(huge(1)/2, wp)))
        case (design_lhs)
            n = sw%nlhs
        case default
            n = 1 + 2*size(sw%params)
        end select
    end function design_runs

    !> The design: v(p, r) is parameter p in member run r (a scale factor for
    !! FAMILY and BODY parameters, the field value for FIELD parameters).
    !! FACTORIAL: every combination of `levels` equally spaced values (log-
    !! spaced for LOG), the first parameter varying fastest. LHS: one value in
    !! each of n equal-probability strata per parameter, strata paired at
    !! random (seeded, same on every machine). OAT: run 1 nominal, then each
    !! parameter in turn at nominal*(1 - step) and nominal*(1 + step).
    function sweep_design(sw) result(v)
        type(sweep_t), intent(in) :: sw   !! the sweep (parameters and design)
        real(wp), allocatable :: v(:, :)
        integer :: np, n, r, p, idx, lev
        real(wp), allocatable :: lhs(:, :)
        np = size(sw%params)
        n = design_runs(sw)
        allocate (v(np, n))
        do r = 1, n
            v(:, r) = sw%params%nominal
        end do
        select case (sw%design)
        case (design_factorial)
            do r = 1, n
                idx = r - 1
                do p = 1, np
                    lev = mod(idx, sw%levels)
                    idx = idx/sw%levels
                    v(p, r) = spread_value(sw%params(p), real(lev, wp)/real(sw%levels - 1, wp))
                end do
            end do
        case (design_lhs)
            lhs = latin_hypercube(np, n, sw%seed)
            do p = 1, np
                do r = 1, n
                    v(p, r) = spread_value(sw%params(p), lhs(p, r))
                end do
            end do
        case (design_oat)
            do p = 1, np
                v(p, 2*p:2*p + 1) = oat_values(sw, p)
            end do
        end select
        ! a FIELD value is what the deck field can hold
        do p = 1, np
            if (sw%params(p)%kind == par_field) then
                do r = 1, n
                    v(p, r) = field_value(v(p, r))
                end do
            end if
        end do
    end function sweep_design

    !> Value at fraction u in [0, 1] of the parameter's range.
    pure real(wp) function spread_value(p, u) result(x)
        type(sweep_param_t), intent(in) :: p   !! the parameter (its range and spacing)
        real(wp), intent(in) :: u              !! fraction of the range, 0 to 1
        if (p%log_spacing) then
            x = exp(log(p%low) + u*(log(p%high) - log(p%low)))
        else
            x = p%low + u*(p%high - p%low)
        end if
        x = min(max(x, p%low), p%high)
    end function spread_value

    !> The two one-at-a-time values of parameter p.
    pure function oat_values(sw, p) result(v)
        type(sweep_t), intent(in) :: sw
        integer, intent(in) :: p
        real(wp) :: v(2)
        v = sw%params(p)%nominal*[one - sw%percent/100.0_wp, one + sw%percent/100.0_wp]
    end function oat_values

    !> The case of one member: the base deck with the FIELD values written
    !! into their fields, read as any deck, then the FAMILY and BODY scale
    !! factors applied to the model. Sampling is made 0.1 ms or finer so
    !! that the injury criteria are computed, unless deck_sampling (a
    !! calibration's reference case: its curves as its result file holds
    !! them, a quasi-static segment test at the deck's 10 ms).
    subroutine sweep_member_case(sw, v, cs, stat, errmsg, deck_sampling)
        type(sweep_t), intent(in) :: sw                !! the sweep (base deck, parameters)
        real(wp), intent(in) :: v(:)                   !! one value per parameter
        type(case_t), intent(out) :: cs                !! the member's case (no result file, sampling 0.1 ms or finer)
        integer, intent(out) :: stat                   !! stat_ok, or the failure of the member's deck or tree
        character(len=msglen), intent(out) :: errmsg   !! why the member's case is invalid ('' when stat_ok)
        logical, intent(in), optional :: deck_sampling !! true: keep the deck's OUTPUT interval (its result file's)
        type(deck_line_t), allocatable :: lines(:)
        integer :: p, c1, c2, k
        logical :: rebuild_tree, keep
        lines = sw%base_lines
        do p = 1, size(sw%params)
            if (sw%params(p)%kind /= par_field .or. .not. sw%params(p)%bound) cycle
            call field_columns(1 + mod(sw%params(p)%field - 1, nfields), c1, c2)
            lines(sw%params(p)%line)%text(c1:c2) = field_text(v(p))
            do k = 1, size(sw%params(p)%ties)
                associate (t => sw%params(p)%ties(k))
                    call field_columns(1 + mod(t%field - 1, nfields), c1, c2)
                    lines(t%line)%text(c1:c2) = field_text(t%a + t%b*v(p))
                end associate
            end do
        end do
        call read_case_lines(lines, trim(sw%base), cs, stat, errmsg, sw%search)
        if (stat /= 0) return
        rebuild_tree = .false.
        do p = 1, size(sw%params)
            if (.not. sw%params(p)%bound) cycle
            associate (q => sw%params(p))
                select case (q%kind)
                case (par_family)
                    call scale_family(cs%model, q%family, q%item, v(p))
                case (par_body)
                    if (q%item == 'MASS') then
                        cs%model%tree%mass(q%body) = v(p)*cs%model%tree%mass(q%body)
                    else
                        cs%model%tree%inertia(:, :, q%body) = v(p)*cs%model%tree%inertia(:, :, q%body)
                        rebuild_tree = .true.
                    end if
                end select
            end associate
        end do
        if (rebuild_tree) then
            call tree_build(cs%model%tree, stat, errmsg)
            if (stat /= 0) return
        end if
        call model_set_neutral(cs%model)     ! disc stiffness and damping matrices
        keep = .false.
        if (present(deck_sampling)) keep = deck_sampling
        if (cs%sample_dt > 1.0e-4_wp .and. .not. keep) cs%sample_dt = 1.0e-4_wp
        cs%h5file = ''
    end subroutine sweep_member_case

    !> Run member `v` of the sweep (listing discarded, no HDF5) and
    !! summarise it. A member that fails keeps its exit code and message.
    subroutine run_member(sw, v, rec)
        type(sweep_t), intent(in) :: sw             !! the sweep
        real(wp), intent(in) :: v(:)                !! the member's parameter values (a column of sweep_design)
        type(member_record_t), intent(out) :: rec   !! exit code, message, summary outputs, effort
        type(case_t) :: cs
        type(run_result_t) :: res
        type(run_state_t) :: run
        integer :: stat, lu, ios
        character(len=msglen) :: msg
        call sweep_member_case(sw, v, cs, stat, msg)
        if (stat /= 0) then
            rec%status = exit_deck
            rec%message = msg
            return
        end if
        open (newunit=lu, file='/dev/null', action='write', iostat=ios)
        if (ios /= 0) then
            rec%status = exit_deck
            rec%message = 'cannot open /dev/null for the discarded listing'
            return
        end if
        call run%execute(cs, lu, '', res, keep_samples=.true.)
        close (lu)
        rec%status = res%exit_code
        rec%t_reached = res%t_reached
        rec%wall = res%wall
        rec%nevals = res%nevals
        if (res%exit_code /= exit_ok) then
            rec%message = res%message
            return
        end if
        rec%message = res%warning
        rec%outputs = member_summary(cs, res)
    end subroutine run_member

    !> The summary outputs (output_names) of a complete run kept with its
    !! samples: head rotation relative to R (HEAD_THETY's signed extreme and
    !! its time; the Bryant angles of the head's rotation matrix and the
    !! total rotation angle), head angular velocity (R axes) and angular
    !! acceleration (CFC 60), peak head resultant acceleration (CFC 1000),
    !! upper-neck loads in head axes (CFC 600), HIC15, the largest Nij mode
    !! and NIC; the head's largest extension relative to T1 (HT1_RY's
    !! lowest value) and when, and the first touch of the deck's contacts
    !! (hn_whiplash's contact_onset on every CONTACT DEPTH channel, the
    !! earliest; -1 ms without contact). Extremes are signed values of
    !! largest magnitude.
    function member_summary(cs, res) result(y)
        type(case_t), intent(in) :: cs           !! the member's case (its channels, sampling interval)
        type(run_result_t), intent(in) :: res    !! the complete run, samples and head matrices kept
        real(wp) :: y(nout)
        type(channel_set_t) :: ch
        real(wp), allocatable :: a(:, :), f(:, :), m(:, :), q(:, :), ang(:)
        real(wp) :: prev(3), t_touch
        logical :: touched
        integer :: k, n, i, at
        call channels_define(cs, ch)
        n = size(res%samples_t)
        y = zero
        k = channel(ch, 'HEAD_THETY')
        at = extreme_index(res%samples(k, :))
        y(1) = res%samples(k, at)
        y(2) = 1000.0_wp*res%samples_t(at)
        y(3) = signed_extreme(res%samples(channel(ch, 'HEAD_OMEGY'), :))
        allocate (a(n, 3), f(n, 3), m(n, 3), q(n, 3), ang(n))
        do i = 1, 3
            call cfc_filter(res%samples(channel(ch, 'HEAD_ALPH'//xyz(i)), :), cs%sample_dt, 60.0_wp, a(:, i))
        end do
        y(4) = signed_extreme(a(:, 2))
        ! head orientation in 3-D
        ! each sample's angles continue the one before (a pitch past 90 deg
        ! is not turned into 180 deg of lateral bending and twist)
        prev = bryant_angles(res%samples_head_s(:, :, 1))
        do i = 1, n
            prev = bryant_angles_near(res%samples_head_s(:, :, i), prev)
            q(i, :) = prev
        end do
        q = q/deg
        do i = 1, n
            ang(i) = rotation_angle(res%samples_head_s(:, :, i))/deg
        end do
        do i = 1, 3
            y(13 + i) = signed_extreme(q(:, i))
        end do
        at = extreme_index(ang)
        y(17) = ang(at)
        y(18) = 1000.0_wp*res%samples_t(at)
        y(19) = signed_extreme(res%samples(channel(ch, 'HEAD_OMEGX'), :))
        y(20) = signed_extreme(res%samples(channel(ch, 'HEAD_OMEGZ'), :))
        y(21) = maxval(sqrt(res%samples(channel(ch, 'HEAD_OMEGX'), :)**2 + res%samples(channel(ch, 'HEAD_OMEGY'), :)**2 &
                            + res%samples(channel(ch, 'HEAD_OMEGZ'), :)**2))
        y(22) = maxval(norm2(a, dim=2))
        if (res%criteria%computed) then
            y(5) = maxval(res%criteria%head_ar)
            y(6) = res%criteria%tension
            y(7) = res%criteria%compression
            y(8) = res%criteria%shear
            y(9) = res%criteria%flexion
            y(10) = res%criteria%extension
            y(11) = res%criteria%hic15
            y(12) = maxval(res%criteria%nij_max)
            y(13) = res%criteria%nic_max
            ! upper-neck loads in every direction, CFC 600 as the criteria's
            do i = 1, 3
                call cfc_filter(res%samples(channel(ch, 'OC_F'//xyz(i)), :), cs%sample_dt, 600.0_wp, f(:, i))
                call cfc_filter(res%samples(channel(ch, 'OC_M'//xyz(i)), :), cs%sample_dt, 600.0_wp, m(:, i))
            end do
            y(23) = signed_extreme(f(:, 1))
            y(24) = signed_extreme(f(:, 2))
            y(25) = maxval(sqrt(f(:, 1)**2 + f(:, 2)**2))
            y(26) = signed_extreme(m(:, 1))
            y(27) = signed_extreme(m(:, 3))
            y(28) = maxval(norm2(m, dim=2))
        end if
        k = channel(ch, 'HT1_RY')
        at = minloc(res%samples(k, :), dim=1)
        y(29) = res%samples(k, at)
        y(30) = 1000.0_wp*res%samples_t(at)
        y(31) = -1.0_wp
        do k = 1, ch%n
            if (ch%group(k) /= 'CONTACT DEPTH') cycle
            call contact_onset(res%samples(k, :), res%samples_t(1), cs%sample_dt, t_touch, touched)
            if (touched .and. (y(31) < zero .or. 1000.0_wp*t_touch < y(31))) y(31) = 1000.0_wp*t_touch
        end do
    end function member_summary

    pure integer function channel(ch, name) result(k)
        type(channel_set_t), intent(in) :: ch
        character(len=*), intent(in) :: name
        k = findloc(ch%name, name, dim=1)
    end function channel

end module hn_sweep
