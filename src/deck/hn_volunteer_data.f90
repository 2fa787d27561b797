!> Volunteer data: the runs of a test series as CSV files (a header line,
!! then one row per time: the time in ms, then one column per run, as in
!! reference/nbdl_15g), read with errors that name the file, the line and
!! the column; and the corridor of a case's volunteers: each channel's
!! file read, every run filtered (SAE J211/1 CFC), converted and
!! differentiated as its `data_channel_t` says, then the point-wise mean
!! and SD and the peaks' mean and SD (hn_rating). Which files, channels
!! and peaks: the calibration deck (docs/sweeps.md). And a reference CSV:
!! a case's reference curves (a specimen corridor's midline, a test's
!! mean) with optional bounds, each channel over its own rows.
module hn_volunteer_data
    use hn_kinds, only: wp, zero, one, msglen
    use hn_status, only: stat_ok, stat_bad_input
    use hn_posix, only: file_kind, kind_name, kind_regular, kind_missing
    use hn_deck_reader, only: parse_real, next_line, int_str, path_len
    use hn_tables, only: gradient
    use hn_filters, only: cfc_filter
    use hn_rating, only: peak_t, corridor_t, runs_corridor
    implicit none
    private

    public :: data_channel_t, read_runs_csv, read_volunteers, reference_data_t, read_reference_csv
    public :: peak_table_t, is_peak_table, read_peak_table

    !> One channel of the volunteers: the file of its runs and what is
    !! done to each run after the CFC filter.
    type :: data_channel_t
        character(len=10) :: name = ''             !! the channel (the model channel it is compared with)
        character(len=path_len) :: file = ''       !! the file of its runs, in the data directory
        logical :: deg_to_rad = .false.            !! the file holds degrees, the channel radians
        logical :: derivative = .false.            !! the channel is the time derivative of the file's runs
    end type data_channel_t

    !> The reference curves of a case (a reference CSV): per channel its
    !! mean and, when the file has them, its lower and upper bounds, given
    !! on rows first..last (one run of rows) of the common times.
    type :: reference_data_t
        character(len=10), allocatable :: name(:)        !! (channel) column names of the means
        real(wp), allocatable :: t(:)                    !! times [ms], evenly spaced
        real(wp), allocatable :: mean(:, :)              !! (time, channel) reference curve (0 outside its rows)
        real(wp), allocatable :: lower(:, :), upper(:, :) !! (time, channel) its bounds (the mean when none)
        logical, allocatable :: bounded(:)               !! (channel) the file gives its bounds
        integer, allocatable :: first(:), last(:)        !! (channel) its first and last row
    end type reference_data_t

    !> Published peaks of a case (a CSV whose first header column is
    !! `peak`): per PEAK card of the calibration its mean and SD, and its
    !! time's where given; `has` marks the peaks the table gives.
    type :: peak_table_t
        logical :: on = .false.                        !! the case's DATA is such a table
        real(wp), allocatable :: mean(:), sd(:)        !! (peak) [the peak's units]
        real(wp), allocatable :: time_mean(:), time_sd(:)   !! (peak) [ms]
        logical, allocatable :: has(:), has_time(:)    !! (peak) given by the table, its time too
    end type peak_table_t

    integer, parameter :: ref_name_len = 10                 !! longest channel name of a reference CSV

    real(wp), parameter :: spacing_tolerance = 1.0e-6_wp   !! relative departure of a time step from the first

contains

    !> Read a CSV file of runs: a header line (its items are counted, not
    !! read), then rows of numbers separated by commas, the first the time
    !! [ms], then one per run; blank lines are skipped. At least two rows
    !! and two runs, times evenly spaced. Errors name the file, the line and
    !! the column (the item number) and what was found.
    subroutine read_runs_csv(file, t, runs, stat, errmsg)
        character(len=*), intent(in) :: file               !! the file
        real(wp), allocatable, intent(out) :: t(:)         !! first column: times [ms]
        real(wp), allocatable, intent(out) :: runs(:, :)   !! (row, run) the other columns
        integer, intent(out) :: stat                       !! stat_ok or stat_bad_input
        character(len=msglen), intent(out) :: errmsg       !! the file, line and column at fault and why
        character(len=:), allocatable :: text, line
        integer :: p, lineno, ncol, nrow
        real(wp), allocatable :: cells(:, :)
        logical, allocatable :: have(:, :)
        call csv_head(file, 'volunteer data ', text, line, p, lineno, ncol, nrow, stat, errmsg)
        if (stat /= stat_ok) return
        stat = stat_bad_input
        if (ncol == 0) then
            errmsg = 'volunteer data '//file//': empty; expected a header line, then a time and one value per run '// &
                     'on each line'
            return
        end if
        if (ncol < 3) then
            errmsg = 'volunteer data '//file//' line '//trim(int_str(lineno))//': the header has '// &
                     trim(int_str(ncol))//' columns; expected the time and at least two runs'
            return
        end if
        call csv_rows(file, 'volunteer data ', text, p, lineno, nrow, ncol, .false., cells, have, errmsg)
        if (len_trim(errmsg) > 0) return
        t = cells(:, 1)
        runs = cells(:, 2:)
        stat = stat_ok
    end subroutine read_runs_csv

    !> The numbers of one row of a CSV file into row; errmsg ', column K:
    !! ...' when an item is not a number, or ': found N items; expected M'.
    !! With `given`, an empty item is allowed: given(k) false, row(k) zero.
    subroutine parse_row(line, row, errmsg, given)
        character(len=*), intent(in) :: line            !! the row's text
        real(wp), intent(out) :: row(:)                 !! its numbers
        character(len=*), intent(out) :: errmsg         !! '' or what is wrong
        logical, intent(out), optional :: given(:)      !! which items are not empty (empty ones allowed)
        integer :: a, b, n
        logical :: ok
        errmsg = ''
        row = 0
        if (present(given)) given = .false.
        a = 1; n = 0
        do
            b = index(line(a:), ',')
            b = merge(len(line) + 1, a + b - 1, b == 0)
            n = n + 1
            if (n <= size(row)) then
                if (present(given) .and. len_trim(line(a:b - 1)) == 0) then
                    row(n) = zero
                else
                    call parse_real(trim(adjustl(line(a:b - 1))), row(n), ok)
                    if (.not. ok) then
                        errmsg = ', column '//trim(int_str(n))//': found "'// &
                                 trim(adjustl(line(a:min(b - 1, a + 40))))//'"; expected a number'
                        return
                    end if
                    if (present(given)) given(n) = .true.
                end if
            end if
            if (b > len(line)) exit
            a = b + 1
        end do
        if (n /= size(row)) errmsg = ': found '//trim(int_str(n))//' items; expected '// &
                                     trim(int_str(size(row)))//' (the time and one value per column, as the '// &
                                     'header has)'
    end subroutine parse_row

    !> Read the volunteers of directory `dir`: for each channel its file
    !! (read_runs_csv; every file of the case with the times and runs of
    !! the first), each run filtered with class `cfc`, converted to radians
    !! and differentiated as the channel says; then their corridor with
    !! the peaks (hn_rating's runs_corridor), each peak's window holding at
    !! least one of the times.
    subroutine read_volunteers(dir, channels, cfc, peaks, vol, stat, errmsg, bad_channel, bad_peak)
        character(len=*), intent(in) :: dir                !! data directory
        type(data_channel_t), intent(in) :: channels(:)    !! the channels, at least one
        real(wp), intent(in) :: cfc                        !! CFC class of the filter: 60, 180, 600 or 1000 [Hz]
        type(peak_t), intent(in) :: peaks(:)               !! the peaks (curve: a channel number)
        type(corridor_t), intent(out) :: vol               !! the volunteers' corridor
        integer, intent(out) :: stat                       !! stat_ok, or stat_bad_input for a missing or bad file
        character(len=msglen), intent(out) :: errmsg       !! the file, line and column at fault and why
        integer, intent(out), optional :: bad_channel      !! the channel whose file is at fault (0: none)
        integer, intent(out), optional :: bad_peak         !! the peak whose window holds no time (0: none)
        real(wp), allocatable :: t(:), t1(:), runs(:, :), ch(:, :, :)
        real(wp) :: dt
        integer :: k, r, nrun
        character(len=:), allocatable :: file, first
        if (present(bad_channel)) bad_channel = 0
        if (present(bad_peak)) bad_peak = 0
        do k = 1, size(channels)
            if (present(bad_channel)) bad_channel = k
            file = trim(dir)//'/'//trim(channels(k)%file)
            call read_runs_csv(file, t, runs, stat, errmsg)
            if (stat /= stat_ok) return
            if (k == 1) then
                t1 = t; nrun = size(runs, 2); first = file
                allocate (ch(size(t), nrun, size(channels)))
                dt = (t(2) - t(1))*1.0e-3_wp
            else if (size(t) /= size(t1) .or. size(runs, 2) /= nrun) then
                stat = stat_bad_input
                write (errmsg, '(a,i0,a,i0,a,i0,a,i0,a)') 'volunteer data '//file//': ', size(runs, 2), ' runs at ', &
                    size(t), ' times; expected those of '//first//' (', nrun, ' runs at ', size(t1), ' times)'
                return
            else if (any(abs(t - t1) > zero)) then
                stat = stat_bad_input
                errmsg = 'volunteer data '//file//': times other than those of '//first//'; expected the same times'
                return
            end if
            do r = 1, nrun
                call cfc_filter(runs(:, r), dt, cfc, ch(:, r, k))
                if (channels(k)%deg_to_rad) ch(:, r, k) = ch(:, r, k)*acos(-one)/180.0_wp
                if (channels(k)%derivative) ch(:, r, k) = gradient(ch(:, r, k), dt)
            end do
        end do
        if (present(bad_channel)) bad_channel = 0
        do k = 1, size(peaks)
            if (.not. any(t1 >= peaks(k)%window(1) .and. t1 <= peaks(k)%window(2))) then
                if (present(bad_peak)) bad_peak = k
                stat = stat_bad_input
                errmsg = 'found the window '//num_text(peaks(k)%window(1))//' to '//num_text(peaks(k)%window(2))// &
                         ' ms of peak '//trim(peaks(k)%name)//', which holds no time of the volunteer data '//first// &
                         ' (times '//num_text(t1(1))//' to '//num_text(t1(size(t1)))// &
                         ' ms); expected a window within the data'
                return
            end if
        end do
        vol = runs_corridor(t1, ch, peaks)
        stat = stat_ok; errmsg = ''
    end subroutine read_volunteers

    !> Read a reference CSV: a header line naming the columns (the first
    !! the time in ms, then per channel NAME, the reference curve, and
    !! optionally NAME_LOW and NAME_HIGH, its bounds, in any order; names
    !! of 1 to 10 characters, no two alike), then rows of numbers
    !! separated by commas, times evenly spaced. A cell may be empty where
    !! a channel has no value; each column's values fill one run of at
    !! least two rows, a bound's the rows of its mean. Errors name the
    !! file, the line and the column and what was found.
    subroutine read_reference_csv(file, ref, stat, errmsg)
        character(len=*), intent(in) :: file               !! the file
        type(reference_data_t), intent(out) :: ref         !! its curves
        integer, intent(out) :: stat                       !! stat_ok or stat_bad_input
        character(len=msglen), intent(out) :: errmsg       !! the file, line and column at fault and why
        character(len=:), allocatable :: text, line
        character(len=64), allocatable :: head(:)
        real(wp), allocatable :: cells(:, :)
        logical, allocatable :: have(:, :)
        integer, allocatable :: rowline(:), kind_of(:), mean_of(:), first(:), last(:)
        integer :: p, lineno, ncol, nrow, k, i, a, b, n
        call csv_head(file, 'reference data ', text, line, p, lineno, ncol, nrow, stat, errmsg)
        if (stat /= stat_ok) return
        stat = stat_bad_input
        if (ncol < 2) then
            errmsg = 'reference data '//file//': found '//trim(int_str(ncol))//' header columns; expected a '// &
                     'header line of the time and at least one channel'
            return
        end if
        ! the header's names
        allocate (head(ncol))
        a = 1
        do k = 1, ncol
            b = index(line(a:)//',', ',') + a - 1
            head(k) = adjustl(line(a:b - 1))
            a = b + 1
        end do
        allocate (kind_of(ncol), mean_of(ncol))
        kind_of = 0; mean_of = 0      ! 1 mean, 2 lower, 3 upper; the mean column of a bound
        do k = 2, ncol
            n = len_trim(head(k))
            kind_of(k) = 1
            if (n > 4) then
                if (head(k)(n - 3:n) == '_LOW') kind_of(k) = 2
            end if
            if (n > 5) then
                if (head(k)(n - 4:n) == '_HIGH') kind_of(k) = 3
            end if
            if (kind_of(k) == 1 .and. (n == 0 .or. n > ref_name_len .or. scan(trim(head(k)), ' ') > 0)) then
                errmsg = 'reference data '//file//' line '//trim(int_str(lineno))//', column '//trim(int_str(k))// &
                         ': found the name "'//trim(head(k))//'"; expected a channel name of 1 to 10 characters '// &
                         '(or NAME_LOW, NAME_HIGH)'
                return
            end if
            if (any(head(2:k - 1) == head(k))) then
                errmsg = 'reference data '//file//' line '//trim(int_str(lineno))//', column '//trim(int_str(k))// &
                         ': found "'//trim(head(k))//'" again; expected each column once'
                return
            end if
        end do
        do k = 2, ncol
            if (kind_of(k) == 1) cycle
            n = len_trim(head(k)) - merge(4, 5, kind_of(k) == 2)
            do i = 2, ncol
                if (kind_of(i) == 1 .and. head(i) == head(k)(1:n)) mean_of(k) = i
            end do
            if (mean_of(k) == 0) then
                errmsg = 'reference data '//file//' line '//trim(int_str(lineno))//', column '//trim(int_str(k))// &
                         ': found the bound "'//trim(head(k))//'" of no column "'//head(k)(1:n)// &
                         '"; expected the bounds of a channel of the file'
                return
            end if
        end do
        do k = 2, ncol
            if (kind_of(k) /= 1) cycle
            if (count(mean_of == k .and. kind_of == 2) /= count(mean_of == k .and. kind_of == 3)) then
                errmsg = 'reference data '//file//' line '//trim(int_str(lineno))//', column '//trim(int_str(k))// &
                         ': channel "'//trim(head(k))//'" has one bound; expected both '//trim(head(k))//'_LOW and '// &
                         trim(head(k))//'_HIGH, or neither'
                return
            end if
        end do
        ! the rows
        call csv_rows(file, 'reference data ', text, p, lineno, nrow, ncol, .true., cells, have, errmsg, rowline)
        if (len_trim(errmsg) > 0) return
        ! each column: one run of rows; a bound on its mean's rows
        allocate (first(ncol), last(ncol))
        do k = 2, ncol
            first(k) = findloc(have(:, k), .true., dim=1)
            last(k) = findloc(have(:, k), .true., dim=1, back=.true.)
            if (last(k) - first(k) < 1 .or. .not. all(have(max(first(k), 1):last(k), k))) then
                if (first(k) == 0) then
                    i = 1
                else
                    i = first(k) + findloc(have(first(k):last(k), k), .false., dim=1) - 1
                    if (i < first(k)) i = first(k)
                end if
                errmsg = 'reference data '//file//' line '//trim(int_str(rowline(i)))//', column '// &
                         trim(int_str(k))//': the values of "'//trim(head(k))//'" are not one run of at least '// &
                         'two rows; expected no empty cell between its first and last value'
                return
            end if
        end do
        do k = 2, ncol
            if (kind_of(k) == 1) cycle
            if (first(k) /= first(mean_of(k)) .or. last(k) /= last(mean_of(k))) then
                errmsg = 'reference data '//file//' line '//trim(int_str(rowline(first(k))))//', column '// &
                         trim(int_str(k))//': the bound "'//trim(head(k))//'" is given on rows other than its '// &
                         'channel''s; expected the rows of "'//trim(head(mean_of(k)))//'"'
                return
            end if
        end do
        n = count(kind_of == 1)
        allocate (ref%name(n), ref%mean(nrow, n), ref%lower(nrow, n), ref%upper(nrow, n), ref%bounded(n), &
                  ref%first(n), ref%last(n))
        ref%t = cells(:, 1)
        i = 0
        do k = 2, ncol
            if (kind_of(k) /= 1) cycle
            i = i + 1
            ref%name(i) = head(k)(1:ref_name_len)
            ref%mean(:, i) = cells(:, k)
            ref%lower(:, i) = cells(:, k); ref%upper(:, i) = cells(:, k)
            ref%bounded(i) = any(mean_of == k)
            do a = 2, ncol
                if (mean_of(a) /= k) cycle
                if (kind_of(a) == 2) ref%lower(:, i) = cells(:, a)
                if (kind_of(a) == 3) ref%upper(:, i) = cells(:, a)
            end do
            ref%first(i) = first(k); ref%last(i) = last(k)
        end do
        stat = stat_ok; errmsg = ''
    end subroutine read_reference_csv

    !> A CSV file's text, its header line (the first line that is not
    !! blank) and its number of columns, where its rows start and how many
    !! rows that are not blank follow; a missing or irregular file or one
    !! that cannot be read refused (`what` starts the message).
    subroutine csv_head(file, what, text, header, p, lineno, ncol, nrow, stat, errmsg)
        character(len=*), intent(in) :: file                  !! the file
        character(len=*), intent(in) :: what                  !! 'volunteer data ' or 'reference data '
        character(len=:), allocatable, intent(out) :: text    !! its whole text
        character(len=:), allocatable, intent(out) :: header  !! its header line ('' when empty)
        integer, intent(out) :: p                             !! where the line after the header starts
        integer, intent(out) :: lineno                        !! the header's line number
        integer, intent(out) :: ncol                          !! the header's items (0: an empty file)
        integer, intent(out) :: nrow                          !! lines after the header that are not blank
        integer, intent(out) :: stat                          !! stat_ok or stat_bad_input
        character(len=msglen), intent(out) :: errmsg          !! why not
        character(len=:), allocatable :: line
        integer :: kind, k, q
        stat = stat_bad_input; errmsg = ''
        p = 1; lineno = 0; ncol = 0; nrow = 0
        header = ''
        kind = file_kind(file)
        if (kind /= kind_regular) then
            if (kind == kind_missing) then
                errmsg = what//file//': no such file'
            else
                errmsg = what//file//' is '//kind_name(kind)//'; expected a regular file'
            end if
            return
        end if
        call read_text(file, text, stat, errmsg)
        if (stat /= stat_ok) return
        do while (p <= len(text))
            call next_line(text, p, line)
            lineno = lineno + 1
            line = strip_cr(line)
            if (len_trim(line) == 0) cycle
            ncol = 1 + count([(line(k:k) == ',', k=1, len_trim(line))])
            header = line
            exit
        end do
        q = p
        do while (q <= len(text))
            call next_line(text, q, line)
            if (len_trim(strip_cr(line)) > 0) nrow = nrow + 1
        end do
        stat = stat_ok
    end subroutine csv_head

    !> The rows of a CSV file after its header (csv_head): each row's
    !! numbers (empty cells allowed with `blanks`, never the time), at
    !! least two rows, the times (column 1) evenly spaced; errmsg names
    !! the file, line and column at fault ('' when all is well).
    subroutine csv_rows(file, what, text, p, lineno, nrow, ncol, blanks, cells, have, errmsg, rowline)
        character(len=*), intent(in) :: file                  !! the file
        character(len=*), intent(in) :: what                  !! 'volunteer data ' or 'reference data '
        character(len=*), intent(in) :: text                  !! its whole text
        integer, intent(in) :: p                              !! where the rows start
        integer, intent(in) :: lineno                         !! the header's line number
        integer, intent(in) :: nrow                           !! rows that are not blank (csv_head)
        integer, intent(in) :: ncol                           !! items per row
        logical, intent(in) :: blanks                         !! empty cells allowed
        real(wp), allocatable, intent(out) :: cells(:, :)     !! (row, column) the numbers (0 where empty)
        logical, allocatable, intent(out) :: have(:, :)       !! (row, column) not empty
        character(len=msglen), intent(out) :: errmsg          !! '' or what is wrong
        integer, allocatable, intent(out), optional :: rowline(:) !! the line number of each row
        character(len=:), allocatable :: line
        real(wp) :: row(ncol)
        logical :: given(ncol)
        integer :: q, ln, n, i, lines(nrow)
        allocate (cells(nrow, ncol), have(nrow, ncol))
        q = p; ln = lineno; n = 0
        errmsg = ''
        do while (q <= len(text))
            call next_line(text, q, line)
            ln = ln + 1
            line = strip_cr(line)
            if (len_trim(line) == 0) cycle
            if (blanks) then
                call parse_row(line, row, errmsg, given)
                if (len_trim(errmsg) == 0 .and. .not. given(1)) &
                    errmsg = ', column 1: found an empty time; expected a number'
            else
                call parse_row(line, row, errmsg)
                given = .true.
            end if
            if (len_trim(errmsg) > 0) then
                errmsg = what//file//' line '//trim(int_str(ln))//trim(errmsg)
                return
            end if
            n = n + 1
            cells(n, :) = row
            have(n, :) = given
            lines(n) = ln
        end do
        if (present(rowline)) rowline = lines
        if (n < 2) then
            errmsg = what//file//': '//trim(int_str(n))//' rows of numbers; expected at least two'
            return
        end if
        associate (t => cells(:, 1))
            do i = 2, n
                if (.not. (t(i) > t(i - 1)) .or. abs((t(i) - t(i - 1)) - (t(2) - t(1))) > &
                    spacing_tolerance*(t(2) - t(1))) then
                    errmsg = what//file//' line '//trim(int_str(lines(i)))//', column 1: found the time '// &
                             num_text(t(i))//' ms after '//num_text(t(i - 1))//' ms (line '// &
                             trim(int_str(lines(i - 1)))//'); expected times evenly spaced as those of the first '// &
                             'two rows'
                    return
                end if
            end do
        end associate
    end subroutine csv_rows

    !> The whole of a file as text.
    subroutine read_text(file, text, stat, errmsg)
        character(len=*), intent(in) :: file
        character(len=:), allocatable, intent(out) :: text
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: u, ios, n
        stat = stat_bad_input
        open (newunit=u, file=file, status='old', action='read', access='stream', form='unformatted', iostat=ios)
        if (ios /= 0) then
            errmsg = 'volunteer data '//file//': cannot be opened'
            return
        end if
        inquire (unit=u, size=n)
        allocate (character(len=max(n, 0)) :: text)
        if (n > 0) read (u, iostat=ios) text
        close (u)
        if (ios /= 0) then
            errmsg = 'volunteer data '//file//': cannot be read'
            return
        end if
        stat = stat_ok
    end subroutine read_text

    !> x as short text: g0 without the trailing zeros of its fraction.
    pure function num_text(x) result(s)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=40) :: buf
        integer :: n
        write (buf, '(g0)') x
        s = trim(adjustl(buf))
        if (index(s, '.') == 0 .or. scan(s, 'EeDd') > 0) return
        n = len(s)
        do while (s(n:n) == '0')
            n = n - 1
        end do
        if (s(n:n) == '.') n = n - 1
        s = s(1:n)
    end function num_text

    pure function strip_cr(line) result(s)
        character(len=*), intent(in) :: line
        character(len=:), allocatable :: s
        s = line
        if (len(s) > 0) then
            if (s(len(s):len(s)) == achar(13)) s = s(1:len(s) - 1)
        end if
    end function strip_cr

    !> True when the file's first line that is not blank starts with the
    !! header column `peak` (a table of published peaks, read_peak_table).
    function is_peak_table(file) result(yes)
        character(len=*), intent(in) :: file   !! the file
        logical :: yes
        character(len=:), allocatable :: text, line
        integer :: p, lineno, ncol, nrow, stat
        character(len=msglen) :: msg
        yes = .false.
        call csv_head(file, 'peak data ', text, line, p, lineno, ncol, nrow, stat, msg)
        if (stat /= stat_ok .or. ncol == 0) return
        yes = adjustl(line(1:index(line//',', ',') - 1)) == 'peak'
    end function is_peak_table

    !> A table of published peaks: the header `peak,mean,sd` or
    !! `peak,mean,sd,time_mean,time_sd`, then one row per peak, its name one
    !! of `names` (the PEAK cards' names) at most once, the SDs positive.
    subroutine read_peak_table(file, names, table, stat, errmsg)
        character(len=*), intent(in) :: file            !! the file
        character(len=*), intent(in) :: names(:)        !! the names of the calibration's peaks
        type(peak_table_t), intent(out) :: table        !! the peaks it gives
        integer, intent(out) :: stat                    !! stat_ok or stat_bad_input
        character(len=msglen), intent(out) :: errmsg    !! the file, line and column at fault and why
        character(len=:), allocatable :: text, line
        character(len=*), parameter :: what = 'peak data '
        real(wp) :: row(5)
        integer :: p, lineno, ncol, nrow, c, k, nv, nitems
        call csv_head(file, what, text, line, p, lineno, ncol, nrow, stat, errmsg)
        if (stat /= stat_ok) return
        stat = stat_bad_input
        if (trim(line) /= 'peak,mean,sd' .and. trim(line) /= 'peak,mean,sd,time_mean,time_sd') then
            errmsg = what//file//' line '//trim(int_str(lineno))//': found the header "'//trim(line(1:min(len(line), &
                     60)))//'"; expected peak,mean,sd or peak,mean,sd,time_mean,time_sd'
            return
        end if
        nv = ncol - 1
        table%on = .true.
        allocate (table%mean(size(names)), table%sd(size(names)), table%time_mean(size(names)), &
                  table%time_sd(size(names)), table%has(size(names)), table%has_time(size(names)))
        table%mean = zero; table%sd = one; table%time_mean = zero; table%time_sd = one
        table%has = .false.; table%has_time = .false.
        do while (p <= len(text))
            call next_line(text, p, line)
            lineno = lineno + 1
            line = strip_cr(line)
            if (len_trim(line) == 0) cycle
            c = index(line//',', ',')
            k = findloc([(adjustl(line(1:c - 1)) == names(k), k=1, size(names))], .true., dim=1)
            if (k == 0) then
                errmsg = what//file//' line '//trim(int_str(lineno))//', column 1: found the peak "'// &
                         trim(adjustl(line(1:min(c - 1, 40))))//'"; expected the name of a PEAK card'
                return
            end if
            if (table%has(k)) then
                errmsg = what//file//' line '//trim(int_str(lineno))//', column 1: found the peak "'// &
                         trim(names(k))//'" again; expected each peak once'
                return
            end if
            nitems = 1 + count([(line(k:k) == ',', k=1, len_trim(line))])
            errmsg = ''
            if (nitems /= ncol) then
                errmsg = ': found '//trim(int_str(nitems))//' items; expected '//trim(int_str(ncol))// &
                         ' (the peak''s name and a value per column of the header)'
            else        ! the name's cell as a number, so that the columns are the file's
                call parse_row('0'//line(c:), row(1:ncol), errmsg)
                row(1:nv) = row(2:ncol)
            end if
            if (len_trim(errmsg) == 0 .and. (row(2) <= zero .or. (nv == 4 .and. row(min(4, nv)) <= zero))) &
                errmsg = ': found an SD of zero or less; expected a positive SD'
            if (len_trim(errmsg) > 0) then
                errmsg = what//file//' line '//trim(int_str(lineno))//trim(errmsg)
                return
            end if
            table%has(k) = .true.
            table%mean(k) = row(1); table%sd(k) = row(2)
            if (nv == 4) then
                table%has_time(k) = .true.
                table%time_mean(k) = row(3); table%time_sd(k) = row(4)
            end if
        end do
        if (.not. any(table%has)) then
            errmsg = what//file//': no rows; expected one row per peak it gives'
            return
        end if
        stat = stat_ok; errmsg = ''
    end subroutine read_peak_table

end module hn_volunteer_data
