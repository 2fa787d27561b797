!> Two-column numeric text files (time, value) for TABLE cards: one pair
!! per line, separated by a comma, a semicolon or blanks; blank lines and
!! lines starting with '#' are skipped, and so is a first line whose first
!! item is not a number (a header such as `time_ms,run_1635`). CR LF line
!! ends read as LF. Numbers are read strictly (hn_deck_reader's parse_real).
module hn_csv
    use hn_kinds, only: wp
    use hn_status, only: stat_ok, stat_bad_input
    use hn_deck_reader, only: parse_real, int_str, next_line
    implicit none
    private

    public :: read_two_columns

contains

    !> The pairs of `text` into t and y (allocated to the number of data
    !! rows). On a line that is not two numbers: stat_bad_input, errmsg
    !! naming the line and what was found.
    subroutine read_two_columns(text, t, y, stat, errmsg)
        character(len=*), intent(in) :: text                 !! the file's contents
        real(wp), allocatable, intent(out) :: t(:)           !! first column (times), in file order
        real(wp), allocatable, intent(out) :: y(:)           !! second column (values), in file order
        integer, intent(out) :: stat                         !! stat_ok or stat_bad_input
        character(len=:), allocatable, intent(out) :: errmsg !! the line at fault and why
        integer :: p, lineno, n, nitems
        character(len=:), allocatable :: line
        character(len=64) :: items(3)
        real(wp) :: a, b
        logical :: ok_a, ok_b, first_data
        stat = stat_ok
        errmsg = ''
        allocate (t(count_lines(text)), y(count_lines(text)))
        n = 0
        lineno = 0
        first_data = .true.
        p = 1
        do while (p <= len(text))
            call next_line(text, p, line)
            lineno = lineno + 1
            if (len(line) > 0) then
                if (line(len(line):len(line)) == achar(13)) line = line(1:len(line) - 1)
            end if
            if (len_trim(line) == 0) cycle
            if (line(1:1) == '#') cycle
            call split(line, items, nitems)
            ok_a = .false.
            if (nitems >= 1) call parse_real(trim(items(1)), a, ok_a)
            if (first_data .and. (nitems == 0 .or. .not. ok_a)) then
                first_data = .false.          ! a header line
                cycle
            end if
            first_data = .false.
            ok_b = .false.
            if (nitems == 2) call parse_real(trim(items(2)), b, ok_b)
            if (nitems /= 2 .or. .not. (ok_a .and. ok_b)) then
                stat = stat_bad_input
                errmsg = 'line '//trim(int_str(lineno))//': found "'//trim(line(1:min(len(line), 60)))// &
                         '"; expected two numbers (time, value) separated by a comma, a semicolon or blanks'
                return
            end if
            n = n + 1
            t(n) = a
            y(n) = b
        end do
        t = t(1:n)
        y = y(1:n)
    end subroutine read_two_columns

    !> Upper bound of the data rows: the number of line ends plus one.
    pure integer function count_lines(text) result(n)
        character(len=*), intent(in) :: text
        integer :: k
        n = 1
        do k = 1, len(text)
            if (text(k:k) == achar(10)) n = n + 1
        end do
    end function count_lines

    !> The items of a line: separated by commas or semicolons when it has
    !! any (blanks around them ignored, an empty item counted), else by
    !! blanks. At most size(items) are kept; nitems counts them all.
    pure subroutine split(line, items, nitems)
        character(len=*), intent(in) :: line
        character(len=*), intent(out) :: items(:)
        integer, intent(out) :: nitems
        character(len=len(line)) :: l
        integer :: k, start
        logical :: hard, in_item
        l = line
        do k = 1, len(l)
            if (l(k:k) == ';') l(k:k) = ','
            if (l(k:k) == achar(9)) l(k:k) = ' '
        end do
        items = ''
        nitems = 0
        hard = index(l, ',') > 0
        if (hard) then
            start = 1
            do k = 1, len(l) + 1
                if (k <= len(l)) then
                    if (l(k:k) /= ',') cycle
                end if
                nitems = nitems + 1
                if (nitems <= size(items)) items(nitems) = adjustl(l(start:k - 1))
                start = k + 1
            end do
        else
            in_item = .false.
            do k = 1, len(l) + 1
                if (k > len(l)) then
                    if (in_item) nitems = nitems + 1
                    if (in_item .and. nitems <= size(items)) items(nitems) = l(start:k - 1)
                else if (l(k:k) == ' ') then
                    if (in_item) then
                        nitems = nitems + 1
                        if (nitems <= size(items)) items(nitems) = l(start:k - 1)
                    end if
                    in_item = .false.
                else if (.not. in_item) then
                    in_item = .true.
                    start = k
                end if
            end do
        end if
    end subroutine split

end module hn_csv
