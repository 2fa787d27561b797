!> The tabulated print listing in the legacy style of crash-victim codes:
!! paged output with a header (code, version, case title, date, page), an
!! echo of the deck under a column ruler, a model summary, time-history
!! tables at the print interval (the main channel groups and those the
!! PRINT cards select, hn_print_card) and a summary of peaks. A value below
!! its channel's resolution (`resolution`) prints as 0.
module hn_listing
    use hn_kinds, only: wp, zero, deg
    use hn_case, only: case_t, deck_line_t
    use hn_channels, only: channel_set_t
    use hn_tree, only: dof_label
    use hn_model, only: family_name, nfamilies, family_count
    use hn_linsolve, only: solver_name
    use hn_assessment, only: assessment_t
    use hn_injury, only: occupants
    use hn_deck_reader, only: upper
    use hn_history, only: history_t
    use hn_print_card, only: print_selects, print_title
    implicit none
    private

    public :: listing_t

    integer, parameter :: page_lines = 60
    !> Channels per time-history table: 9 + 12*9 = 117 columns, inside the
    !! pages' 118-column frame of a 132-column listing.
    integer, parameter :: cols_per_table = 9
    !> A channel's resolution: this fraction of the largest magnitude of the
    !! listed channels of its unit over the run (docs/output-format.md).
    real(wp), parameter, public :: resolution_fraction = 1.0e-6_wp

    !> A paged listing on one output unit.
    type :: listing_t
        integer :: unit = 6
        integer :: page = 0
        integer :: line = page_lines
        character(len=80) :: title = ''
        character(len=117) :: subtitle = ''   !! the titles of INCLUDEd case decks ('' when none)
        character(len=20) :: stamp = ''
        character(len=16) :: version = ''
    contains
        procedure :: start => listing_start
        procedure :: put => listing_put
        procedure :: new_page => listing_new_page
        procedure :: need => listing_need
        procedure :: echo_deck => listing_echo_deck
        procedure :: model_summary => listing_model_summary
        procedure :: listing_histories, listing_histories_store
        generic :: histories => listing_histories, listing_histories_store
        procedure :: peaks => listing_peaks
        procedure :: message => listing_message
        procedure :: criteria => listing_criteria
    end type listing_t

    !> Row r of a time-history source: its time t [s] and every channel's value v.
    abstract interface
        subroutine row_source(r, t, v)
            import :: wp
            integer, intent(in) :: r
            real(wp), intent(out) :: t, v(:)
        end subroutine row_source
    end interface

contains

    !> Set the header fields; the date and time are taken now. Subtitles
    !! (the titles of the case decks a variant deck INCLUDEs) make a second
    !! title line on every page: "INCLUDES: title; title".
    subroutine listing_start(me, unit, title, version, subtitles)
        class(listing_t), intent(inout) :: me
        integer, intent(in) :: unit               !! output unit of the listing (6: stdout)
        character(len=*), intent(in) :: title     !! deck title for the page headers (80 characters kept)
        character(len=*), intent(in) :: version   !! program version for the page headers
        character(len=*), intent(in), optional :: subtitles(:)  !! titles of INCLUDEd decks (none: one title line)
        character(len=8) :: d
        character(len=10) :: t
        character(len=:), allocatable :: sub
        integer :: k
        me%unit = unit
        me%title = title
        me%version = version
        me%subtitle = ''
        if (present(subtitles)) then
            if (size(subtitles) > 0) then
                sub = 'INCLUDES: '//trim(subtitles(1))
                do k = 2, size(subtitles)
                    sub = sub//'; '//trim(subtitles(k))
                end do
                me%subtitle = sub
            end if
        end if
        call date_and_time(date=d, time=t)
        me%stamp = d(1:4)//'-'//d(5:6)//'-'//d(7:8)//' '//t(1:2)//':'//t(3:4)//':'//t(5:6)
        me%line = page_lines
    end subroutine listing_start

    subroutine listing_new_page(me)
        class(listing_t), intent(inout) :: me
        me%page = me%page + 1
        if (me%page > 1) write (me%unit, '(a)') ''
        write (me%unit, '(a)') repeat('=', 118)
        write (me%unit, '(a,a,t24,a,t88,a,t109,a,i5)') ' HHNECK ', trim(me%version), &
            '3-D HEAD/NECK MODEL AFTER HUSTON, HUSTON & HARLOW (1978)', trim(me%stamp), 'PAGE', me%page
        write (me%unit, '(1x,a)') trim(me%title)
        me%line = 4
        if (len_trim(me%subtitle) > 0) then
            write (me%unit, '(1x,a)') trim(me%subtitle)
            me%line = 5
        end if
        write (me%unit, '(a)') repeat('=', 118)
    end subroutine listing_new_page

    !> Start a new page unless n more lines fit on this one.
    subroutine listing_need(me, n)
        class(listing_t), intent(inout) :: me
        integer, intent(in) :: n   !! lines about to be written together
        if (me%line + n > page_lines) call me%new_page()
    end subroutine listing_need

    !> One line of the listing.
    subroutine listing_put(me, s)
        class(listing_t), intent(inout) :: me
        character(len=*), intent(in) :: s   !! the line (trailing blanks dropped)
        call me%need(1)
        write (me%unit, '(a)') trim(s)
        me%line = me%line + 1
    end subroutine listing_put

    !> A boxed message (run status, errors).
    subroutine listing_message(me, s)
        class(listing_t), intent(inout) :: me
        character(len=*), intent(in) :: s   !! the message
        call me%need(3)
        call me%put('')
        call me%put(' *** '//trim(s))
        call me%put('')
    end subroutine listing_message

    !> Echo of the card images under a column ruler.
    subroutine listing_echo_deck(me, deck)
        class(listing_t), intent(inout) :: me
        type(deck_line_t), intent(in) :: deck(:)   !! card images with their sources and lines
        integer :: k
        character(len=140) :: s
        call me%new_page()
        call me%put(' ECHO OF THE INPUT DECK (comment cards omitted, INCLUDE files expanded)')
        call me%put('')
        call me%put('  CARD  SOURCE:LINE                   '//'         1         2         3         4         5'// &
                    '         6         7         8')
        call me%put('                                      '//repeat('1234567890', 8))
        do k = 1, size(deck)
            write (s, '(i6,2x,a29,1x,a)') k, source_tag(deck(k)%source, deck(k)%line), deck(k)%text
            call me%put(s)
        end do
    end subroutine listing_echo_deck

    pure function source_tag(source, line) result(s)
        character(len=*), intent(in) :: source
        integer, intent(in) :: line
        character(len=29) :: s
        character(len=12) :: num
        integer :: k
        write (num, '(i0)') line
        k = index(source, '/', back=.true.)
        s = source(k + 1:)
        s = trim(s(1:min(len_trim(s), 28 - len_trim(num))))//':'//trim(num)
    end function source_tag

    subroutine listing_model_summary(me, cs)
        class(listing_t), intent(inout) :: me
        type(case_t), intent(in) :: cs   !! the run case (model tables, run control)
        character(len=160) :: s
        character(len=12) :: pname, status, num
        character(len=40) :: item
        character(len=:), allocatable :: line
        integer :: k, j, f, n, nfree, npres
        associate (tr => cs%model%tree, md => cs%model)
            n = tr%ndof
            npres = count(md%prescribed)
            nfree = n - npres
            call me%new_page()
            call me%put(' MODEL SUMMARY')
            call me%put('')
            write (s, '(a,i3,a,i3,a,i3,a,i3,a,i3,a)') '   BODIES', tr%nbody, '   COORDINATES', 6*tr%nbody, &
                '   ACTIVE', n, ' (FREE', nfree, ', PRESCRIBED', npres, ')'
            call me%put(s)
            write (s, '(a,i3)') '   LOCKED COORDINATES', 6*tr%nbody - n
            call me%put(s)
            write (s, '(5a)') '   HEAD BODY ', trim(tr%name(cs%head)), '   T1 BODY ', trim(tr%name(cs%t1)), &
                '   OCCIPITAL CONDYLE (OC) = JOINT POINT OF THE HEAD BODY'
            call me%put(s)
            call me%put('')
            call me%put('   NO. BODY         PARENT         MASS       IXX        IYY        IZZ      '// &
                        'JOINT IN PARENT (M)        JOINT IN BODY (M)')
            call me%put('                                   (KG)    (KG M2)    (KG M2)    (KG M2)')
            do k = 1, tr%nbody
                if (tr%parent(k) == 0) then
                    pname = 'R'
                else
                    pname = tr%name(tr%parent(k))
                end if
                write (s, '(i6,1x,a12,1x,a12,f8.3,3es11.3,2(1x,3f8.4))') k, tr%name(k), pname, tr%mass(k), &
                    (tr%inertia(j, j, k), j=1, 3), tr%joint_parent(:, k), tr%joint_child(:, k)
                call me%put(s)
            end do
            call me%put('')
            call me%put('   ACTIVE COORDINATES (TRANSLATIONS M, M/S; BRYANT ANGLES DEG, DEG/S)')
            call me%put('   NO. COORDINATE        STATUS        INITIAL        RATE')
            do j = 1, n
                status = merge('PRESCRIBED', 'FREE      ', md%prescribed(j))
                f = tr%dof_local(j)
                write (s, '(i6,1x,a15,3x,a10,2f13.5)') j, dof_label(tr, j), status, &
                    cs%x0(j)/merge(1.0_wp, deg, f <= 3), cs%xd0(j)/merge(1.0_wp, deg, f <= 3)
                call me%put(s)
            end do
            call me%put('')
            call me%put('   ELEMENTS')
            ! the families side by side, a new line before one that would pass column 132
            line = '  '
            do f = 1, nfamilies()
                write (item, '(3x,a,1x,i3,1x,a)') trim(family_name(f)), family_count(md, f), &
                    merge('(ON) ', '(OFF)', md%family_on(f))
                k = len_trim(item) + merge(1, 0, md%family_on(f))
                if (len(line) + k > 132) then
                    call me%put(line)
                    line = '  '
                end if
                line = line//item(1:k)
            end do
            call me%put(line)
            write (s, '(a,i3)') '   APPLIED FORCE/COUPLE TABLES', size(md%applied)
            call me%put(s)
            call me%put('')
            if (allocated(cs%warnings)) then
                do k = 1, size(cs%warnings)
                    call me%put('   WARNING: '//trim(cs%warnings(k)))
                end do
            end if
            if (size(cs%scene) == 0) then
                call me%put('   SCENE: THE WHOLE MODEL OF THE DECK (NO SCENE, MERGE, FAMILY OFF OR DROPPED CARDS)')
            else
                call me%put('   SCENE:')
                do k = 1, size(cs%scene)
                    call me%put('     '//trim(cs%scene(k)))
                end do
            end if
            if (allocated(cs%changes)) then
                if (size(cs%changes) > 0) then
                    call me%put('   CHANGES FOR THIS RUN (CHANGE CARDS):')
                    do k = 1, size(cs%changes)
                        call me%put('     '//trim(cs%changes(k)))
                    end do
                end if
            end if
            if (cs%hold_prestrain) then
                call me%put('   POSTURE SETTLED AT THE START: DISCS AND NEUTRAL-ZONE SPRINGS PRE-STRAINED (HOLD PRESTRAIN)')
                call me%put('     '//trim(cs%hold_note))
            end if
            if (cs%hold_posture .and. md%hold_release >= huge(md%hold_release)) then
                call me%put('   POSTURE HELD AT THE START BY CONSTANT GENERALIZED FORCES (HOLD POSTURE)')
            else if (cs%hold_posture) then
                write (num, '(f12.4)') md%hold_release
                s = '   POSTURE HELD AT THE START BY CONSTANT GENERALIZED FORCES (HOLD POSTURE), RELEASED AT T = '// &
                    trim(adjustl(num))//' S'
                if (md%hold_duration > zero) then
                    write (num, '(f12.4)') md%hold_duration
                    s = trim(s)//' OVER '//trim(adjustl(num))//' S'
                else
                    s = trim(s)//' AS A STEP'
                end if
                call me%put(trim(s))
            end if
            call me%put('')
            write (s, '(a,a,a,es10.3,a,es10.3,a,es10.3,a,es9.2,a,es9.2)') '   INTEGRATOR ', trim(cs%integrator), &
                '   STEP', cs%h, ' S   PRINT', cs%print_dt, ' S   SAMPLE', cs%sample_dt, ' S   RTOL', cs%rtol, &
                '   ATOL', cs%atol
            call me%put(s)
            write (s, '(a,f9.4,a,f9.4,a,a,a,3f9.4,a)') '   TIME', cs%t_start, ' TO', cs%t_end, ' S   SOLVER ', &
                solver_name(md%solver), '   GRAVITY', md%gravity, ' M/S2'
            call me%put(s)
        end associate
    end subroutine listing_model_summary

    !> A number in 11 columns: fixed point when readable, else exponent.
    pure function num(v) result(s)
        real(wp), intent(in) :: v
        character(len=11) :: s
        real(wp) :: a
        a = abs(v)
        if (v /= v) then
            s = '        NaN'
        else if (a == zero .or. (a >= 1.0e-2_wp .and. a < 1.0e5_wp)) then
            write (s, '(f11.3)') v
        else
            write (s, '(es11.3)') v
        end if
    end function num

    !> The value a listing prints for v: 0 below the channel's resolution r.
    elemental real(wp) function shown(v, r)
        real(wp), intent(in) :: v   !! the channel's value
        real(wp), intent(in) :: r   !! its resolution (`resolution`)
        shown = merge(zero, v, abs(v) < r)
    end function shown

    !> Each channel's resolution in the listing: resolution_fraction of the
    !! largest magnitude over the run of the listed channels of its unit
    !! (their extremes vmax, vmin; an extreme never set, +-huge, counts 0).
    pure function resolution(ch, vmax, vmin) result(r)
        type(channel_set_t), intent(in) :: ch   !! channel units, listed
        real(wp), intent(in) :: vmax(:)         !! largest value of each channel
        real(wp), intent(in) :: vmin(:)         !! smallest value of each channel
        real(wp) :: r(ch%n)
        real(wp) :: a(ch%n)
        integer :: k
        a = max(abs(vmax), abs(vmin))
        where (.not. (a < huge(a))) a = zero      ! unset extremes; NaN
        do k = 1, ch%n
            r(k) = resolution_fraction*maxval(a, mask=ch%listed .and. ch%units == ch%units(k))
        end do
    end function resolution

    !> Time-history tables from a history store whose rows are (t, channel values).
    subroutine listing_histories_store(me, ch, store, cs, vmax, vmin)
        class(listing_t), intent(inout) :: me
        type(channel_set_t), intent(in) :: ch   !! channel names, units, groups
        type(history_t), intent(in) :: store    !! rows of 1 + ch%n values
        type(case_t), intent(in) :: cs          !! the case: its PRINT cards' selection
        real(wp), intent(in) :: vmax(:)         !! largest value of each channel over the run (resolution)
        real(wp), intent(in) :: vmin(:)         !! smallest value of each channel over the run
        call tables(me, ch, store%n, row_of, cs, resolution(ch, vmax, vmin))
    contains
        subroutine row_of(r, t, v)
            integer, intent(in) :: r
            real(wp), intent(out) :: t, v(:)
            real(wp) :: row(store%m)
            call store%get(r, row)
            t = row(1)
            v = row(2:)
        end subroutine row_of
    end subroutine listing_histories_store

    !> Time-history tables of the channels the case's PRINT cards select
    !! (`tables`) from arrays.
    subroutine listing_histories(me, ch, times, rows, nrows, cs, vmax, vmin)
        class(listing_t), intent(inout) :: me
        type(channel_set_t), intent(in) :: ch   !! channel names, units, groups
        real(wp), intent(in) :: times(:)        !! print times [s]
        real(wp), intent(in) :: rows(:, :)      !! (channels, rows) channel values at those times
        integer, intent(in) :: nrows            !! rows to print
        type(case_t), intent(in) :: cs          !! the case: its PRINT cards' selection
        real(wp), intent(in) :: vmax(:)         !! largest value of each channel over the run (resolution)
        real(wp), intent(in) :: vmin(:)         !! smallest value of each channel over the run
        call tables(me, ch, nrows, row_of, cs, resolution(ch, vmax, vmin))
    contains
        subroutine row_of(r, t, v)
            integer, intent(in) :: r
            real(wp), intent(out) :: t, v(:)
            t = times(r)
            v = rows(:, r)
        end subroutine row_of
    end subroutine listing_histories

    !> The time-history tables, at most cols_per_table channels each, of the
    !! listed channels the PRINT cards select (hn_print_card: the main groups
    !! without one). Under PRINT ALL one table per run of channels of one
    !! group (the listing of earlier versions); else the selected channels
    !! packed into full tables, in channel order, named by their keywords.
    subroutine tables(me, ch, nrows, row_of, cs, res)
        class(listing_t), intent(inout) :: me
        type(channel_set_t), intent(in) :: ch
        integer, intent(in) :: nrows
        procedure(row_source) :: row_of
        type(case_t), intent(in) :: cs
        real(wp), intent(in) :: res(:)
        character(len=10), allocatable :: selected(:)
        logical :: sel(ch%n), full
        integer :: cols(cols_per_table), nc, k, j
        character(len=200) :: title
        character(len=40) :: last
        allocate (selected(0))
        if (allocated(cs%print_groups)) selected = cs%print_groups
        full = any(selected == 'ALL')
        sel = [(ch%listed(k) .and. print_selects(selected, ch%group(k)), k=1, ch%n)]
        k = 1
        do while (k <= ch%n)
            if (.not. sel(k)) then
                k = k + 1
                cycle
            end if
            nc = 1
            cols(1) = k
            k = k + 1
            do while (k <= ch%n .and. nc < cols_per_table)
                if (full) then
                    if (.not. sel(k) .or. ch%group(k) /= ch%group(cols(1))) exit
                else if (.not. sel(k)) then
                    k = k + 1
                    cycle
                end if
                nc = nc + 1
                cols(nc) = k
                k = k + 1
            end do
            if (full) then
                title = ch%group(cols(1))
            else
                last = print_title(ch%group(cols(1)))
                title = last
                do j = 2, nc
                    if (print_title(ch%group(cols(j))) == last) cycle
                    last = print_title(ch%group(cols(j)))
                    title = trim(title)//', '//last
                end do
            end if
            call table(me, ch, cols(1:nc), trim(title), nrows, row_of, res)
        end do
    end subroutine tables

    !> One time-history table: channels `cols`, every row, on as many pages as it takes.
    subroutine table(me, ch, cols, title, nrows, row_of, res)
        class(listing_t), intent(inout) :: me
        type(channel_set_t), intent(in) :: ch
        integer, intent(in) :: cols(:)
        character(len=*), intent(in) :: title
        integer, intent(in) :: nrows
        procedure(row_source) :: row_of
        real(wp), intent(in) :: res(:)
        real(wp) :: t, v(ch%n)
        integer :: j, r, line_len
        character(len=200) :: s, h1, h2
        h1 = '    TIME '
        h2 = '    (MS) '
        do j = 1, size(cols)
            h1 = h1(1:9 + 12*(j - 1))//' '//adjustr(ch%name(cols(j))(1:11))
            h2 = h2(1:9 + 12*(j - 1))//' '//adjustr(ch%units(cols(j))(1:11))
        end do
        line_len = 9 + 12*size(cols)
        call me%new_page()
        call me%put(' TIME HISTORY: '//title)
        call me%put('')
        call me%put(h1(1:line_len))
        call me%put(h2(1:line_len))
        do r = 1, nrows
            if (me%line + 1 > page_lines) then
                call me%new_page()
                call me%put(' TIME HISTORY: '//title//' (CONTINUED)')
                call me%put('')
                call me%put(h1(1:line_len))
                call me%put(h2(1:line_len))
            end if
            call row_of(r, t, v)
            write (s, '(f9.2)') 1000*t
            do j = 1, size(cols)
                s = s(1:9 + 12*(j - 1))//' '//num(shown(v(cols(j)), res(cols(j))))
            end do
            call me%put(s(1:line_len))
        end do
    end subroutine table

    !> Summary of peaks of every listed channel (from the full sampled
    !! histories); an extreme below the channel's resolution prints as 0.
    subroutine listing_peaks(me, ch, vmax, tmax, vmin, tmin)
        class(listing_t), intent(inout) :: me
        type(channel_set_t), intent(in) :: ch   !! channel names and units
        real(wp), intent(in) :: vmax(:)         !! largest value of each channel
        real(wp), intent(in) :: tmax(:)         !! when [s]
        real(wp), intent(in) :: vmin(:)         !! smallest value of each channel
        real(wp), intent(in) :: tmin(:)         !! when [s]
        integer :: k
        character(len=120) :: s
        real(wp) :: res(ch%n)
        res = resolution(ch, vmax, vmin)
        call me%new_page()
        call me%put(' SUMMARY OF PEAKS (ALL SAMPLES)')
        call me%put('')
        call me%put('   CHANNEL                  UNITS          MAXIMUM   AT (MS)      MINIMUM   AT (MS)')
        do k = 1, ch%n
            if (.not. ch%listed(k)) cycle
            write (s, '(3x,a24,1x,a12,a11,f10.2,2x,a11,f10.2)') ch%name(k), ch%units(k), &
                num(shown(vmax(k), res(k))), 1000*tmax(k), num(shown(vmin(k), res(k))), 1000*tmin(k)
            call me%put(s)
        end do
    end subroutine listing_peaks

    !> Injury criteria with the reference values of the chosen occupant's
    !! dummy (hn_injury's occupants) and, under the table, each criterion's
    !! source and where it applies. The run's loading direction (hn_whiplash's
    !! scene_direction) picks the rows: a frontal or rear run shows the
    !! sagittal criteria, a lateral run the lateral ones; the others are named
    !! as not applicable (the result file holds them all).
    subroutine listing_criteria(me, a)
        class(listing_t), intent(inout) :: me
        type(assessment_t), intent(in) :: a   !! the run's injury assessment
        character(len=120) :: s
        character(len=3), parameter :: modes(4) = ['NTE', 'NTF', 'NCE', 'NCF']
        character(len=*), parameter :: ms = ' MS'
        logical :: lateral
        integer :: k
        call me%need(44)
        call me%put('')
        call me%put(' INJURY CRITERIA (HEAD ACCELERATION CFC 1000, UPPER-NECK LOADS CFC 600, NIC CFC 60)')
        call me%put('')
        if (.not. a%computed) then
            call me%put('   '//trim(a%note))
            return
        end if
        lateral = a%direction == 'LATERAL'
        call me%put('   LOADING DIRECTION      '//trim(a%direction)//'  [5]')
        associate (occ => occupants(a%occupant))
            write (s, '(a,f10.1,a,f8.2,a,f8.2,a)') '   HIC15                  ', a%hic15, '   FROM', 1000*a%hic15_t1, &
                ' TO', 1000*a%hic15_t2, ' MS          REF     700  [1]'
            call me%put(s)
            write (s, '(a,f10.1,a,f8.2,a,f8.2,a)') '   HIC36                  ', a%hic36, '   FROM', 1000*a%hic36_t1, &
                ' TO', 1000*a%hic36_t2, ' MS          REF    1000  [1]'
            call me%put(s)
            if (.not. lateral) then
                do k = 1, 4
                    write (s, '(a,a,a,f10.3,a,f8.2,a)') '   NIJ ', modes(k), '                ', a%nij_max(k), &
                        '   AT ', 1000*a%nij_time(k), ' MS                          REF     1.0  [2]'
                    call me%put(s)
                end do
                write (s, '(a,f10.2,a,f8.2,a)') '   NIC (M2/S2)            ', a%nic_max, '   AT ', 1000*a%nic_time, &
                    ' MS                          REF      15  [3] (REAR-IMPACT CRITERION)'
                call me%put(s)
            end if
            write (s, '(a,f10.1,a,f8.2,a,i7,a)') '   UPPER NECK TENSION (N) ', a%tension, '   AT ', &
                1000*a%tension_t, ' MS                          REF ', nint(occ%tension), '  [4]'
            call me%put(s)
            write (s, '(a,f10.1,a,f8.2,a,i7,a)') '   COMPRESSION (N)        ', a%compression, '   AT ', &
                1000*a%compression_t, ' MS                          REF ', -nint(occ%compression), '  [4]'
            call me%put(s)
            if (lateral) then
                call row('   LAT. MOMENT |MX| (N M)', a%lat_moment, a%lat_moment_t, '')
                call row('   LAT. SHEAR |FY| (N)', a%lat_shear, a%lat_shear_t, '')
                call row('   HEAD LAT. BENDING (DEG)', a%lat_bend, a%lat_bend_t, '  [7]')
                call me%put('   NOT APPLICABLE TO A LATERAL RUN (IN THE RESULT FILE): NIJ, NIC, NDC, SAGITTAL SHEAR '// &
                            'AND MOMENTS')
            else
                call row('   SHEAR |FX| (N)', a%shear, a%shear_t, '')
                call row('   FLEXION MOMENT (N M)', a%flexion, a%flexion_t, '')
                call row('   EXTENSION MOMENT (N M)', a%extension, a%extension_t, '')
                call row('   T1 X ACCELERATION (G)', a%t1_ax_max, a%t1_ax_max_t, '  [3]')
                call row('   HEAD X ACCELERATION (G)', a%head_ax_max, a%head_ax_max_t, '  [3]')
                write (s, '(a,f10.1,a,f8.2,a,f8.1,a)') '   NDC EXTENSION (DEG)    ', a%ndc%ext_angle, '   AT ', &
                    1000*a%ndc%ext_time, ' MS   HEAD X', a%ndc%ext_dx, ' MM  [6]'
                call me%put(s)
                write (s, '(a,f10.1,a,f8.2,a,f8.1,a)') '   NDC RETRACTION (MM)    ', a%ndc%ret_dx, '   AT ', &
                    1000*a%ndc%ret_time, ' MS   ANGLE ', a%ndc%ret_angle, ' DEG  [6]'
                call me%put(s)
                call me%put('   NKM, LNL                NOT COMPUTED: INTERCEPTS NOT SOURCED  [6]')
                call me%put('   IV-NIC                  NOT COMPUTED: JOINT ROTATIONS NOT PASSED TO THE ASSESSMENT  [6]')
                call me%put('   NOT APPLICABLE TO A '//trim(a%direction)//' RUN (IN THE RESULT FILE): LATERAL MOMENT, '// &
                            'LATERAL SHEAR, HEAD LATERAL BENDING')
            end if
            call me%put('')
            call me%put('   REF: INJURY ASSESSMENT REFERENCE VALUE OF A CRASH-TEST DUMMY IN A STANDARD, NOT A LIMIT OF '// &
                        'THIS HUMAN MODEL')
            call me%put('   [1] 49 CFR 571.208 S6.2 (FMVSS 208): HEAD MASS-CENTRE RESULTANT ACCELERATION, CFC 1000')
            if (.not. lateral) then
                call me%put('   [2] '//trim(upper(occ%source))//': UPPER NECK (OCCIPITAL CONDYLE), CFC 600; '// &
                            'INTERCEPTS OF THE '//trim(occ%label))
                write (s, '(a,i0,a,i0,a,i0,a,i0,a)') '       FZC ', nint(occ%crit%fz_tension), ' N TENSION, ', &
                    nint(occ%crit%fz_compression), ' N COMPRESSION; MYC ', nint(occ%crit%my_flexion), &
                    ' N M FLEXION, ', nint(occ%crit%my_extension), ' N M EXTENSION'
                call me%put(s)
                call me%put('   [3] BOSTROM ET AL. 1996: REAR IMPACT ONLY, NOT A CRITERION FOR FRONTAL OR LATERAL '// &
                            'LOADING; CFC 60')
                if (a%nic_frame == 'HEAD') then
                    call me%put('       X-ACCELERATIONS OF T1 AND THE HEAD ALONG THE HEAD''S X AXIS')
                else
                    call me%put('       X-ACCELERATIONS OF T1 AND THE HEAD ALONG THE INERTIAL X AXIS')
                end if
            end if
            call me%put('   [4] '//trim(upper(occ%source))//': UPPER NECK, CFC 600; '//trim(occ%label))
            if (.not. occ%verified) &
                call me%put('       ('//trim(occ%code)//' PEAK VALUES NOT VERIFIED AGAINST THE REGULATION TEXT)')
            call me%put('   [5] LATERAL IF THE LARGEST |HT1_RX| EXCEEDS THE LARGEST |HT1_RY|; ELSE REAR IF THE '// &
                        'LARGEST HT1_RY IS AN EXTENSION, FRONTAL IF A FLEXION')
            if (lateral) then
                call me%put('   [7] HT1_RX: THE HEAD''S LATERAL BENDING RELATIVE TO T1 (> 0 TOP OF THE HEAD TO THE '// &
                            'RIGHT); NO REFERENCE VALUE')
            else
                call me%put('   [6] NDC (MUSER ET AL. 2000): HEAD RELATIVE TO T1 (HT1_RY, HT1_DX); CORRIDORS NOT '// &
                            'SOURCED, NOT COMPARED')
                call me%put('       NKM (SCHMITT ET AL. 2002), LNL (HEITPLATZ ET AL. 2003), IV-NIC (PANJABI ET AL. '// &
                            '1999): DOCS/OUTPUT-FORMAT.MD')
            end if
        end associate
    contains
        subroutine row(label, v, t, tail)
            character(len=*), intent(in) :: label, tail
            real(wp), intent(in) :: v, t
            character(len=26) :: l
            l = label
            write (s, '(a,f10.1,a,f8.2,a)') l, v, '   AT ', 1000*t, ms//tail
            call me%put(s)
        end subroutine row
    end subroutine listing_criteria

end module hn_listing
