!> Reading card images: lines from standard input and INCLUDE files, the
!! fixed columns of a card, and strict conversion of fields with errors
!! that name the source, line, columns, card, field, what was found and
!! what was expected.
!!
!! Card layout (80 columns): columns 1-8 the card name, 9-10 blank, then
!! seven fields of ten columns: F1 = 11-20, F2 = 21-30, ... F7 = 71-80.
!! A card whose columns 1-10 are blank continues the card above it.
!! '*' in column 1 marks a comment; blank lines are ignored. CR LF line ends
!! read as LF line ends; a carriage return anywhere else is an error.
module hn_deck_reader
    use hn_kinds, only: wp, msglen, i8
    use hn_status, only: stat_bad_input
    use hn_case, only: deck_line_t, path_len
    implicit none
    private

    public :: deck_reader_t, read_card_images, field_columns, int_str, upper

    integer, parameter, public :: nfields = 7
    integer, parameter :: max_include_depth = 4

    !> The card images of a deck and the first error met while reading them.
    type :: deck_reader_t
        type(deck_line_t), allocatable :: lines(:)
        integer :: nlines = 0
        character(len=:), allocatable :: top   !! name of the deck itself in messages
        integer :: stat = 0
        character(len=msglen) :: errmsg = ''
    contains
        procedure :: failed => reader_failed
        procedure :: fail => reader_fail
        procedure :: key => reader_key
        procedure :: raw => reader_raw
        procedure :: is_blank => reader_is_blank
        procedure :: real => reader_real
        procedure :: int => reader_int
        procedure :: name => reader_name
        procedure :: text => reader_text
        procedure :: where => reader_where
        procedure :: context
    end type deck_reader_t

contains

    !> First and last column of field f (1..7).
    pure subroutine field_columns(f, c1, c2)
        integer, intent(in) :: f
        integer, intent(out) :: c1, c2
        c1 = 1 + 10*f
        c2 = c1 + 9
    end subroutine field_columns

    logical function reader_failed(me)
        class(deck_reader_t), intent(in) :: me
        reader_failed = me%stat /= 0
    end function reader_failed

    !> Record the first error only.
    subroutine reader_fail(me, msg)
        class(deck_reader_t), intent(inout) :: me
        character(len=*), intent(in) :: msg
        if (me%stat /= 0) return
        me%stat = stat_bad_input
        me%errmsg = msg
    end subroutine reader_fail

    !> "stdin line 12" for deck line i.
    function reader_where(me, i) result(s)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i
        character(len=:), allocatable :: s
        character(len=16) :: num
        write (num, '(i0)') me%lines(i)%line
        s = me%lines(i)%source//' line '//trim(num)
    end function reader_where

    !> Card name of line i (columns 1-8, upper case).
    function reader_key(me, i) result(k)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i
        character(len=8) :: k
        k = upper(me%lines(i)%text(1:8))
    end function reader_key

    !> Raw text of field f of line i, adjusted left.
    function reader_raw(me, i, f) result(s)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i, f
        character(len=10) :: s
        integer :: c1, c2
        call field_columns(f, c1, c2)
        s = adjustl(me%lines(i)%text(c1:c2))
    end function reader_raw

    logical function reader_is_blank(me, i, f)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i, f
        reader_is_blank = len_trim(me%raw(i, f)) == 0
    end function reader_is_blank

    !> Context of an error in field f of line i: "stdin line 4, columns
    !! 31-40 (BODY card, field F3 'mass')".
    function context(me, i, f, what) result(s)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i, f
        character(len=*), intent(in) :: what
        character(len=:), allocatable :: s
        character(len=40) :: cols
        integer :: c1, c2
        call field_columns(f, c1, c2)
        write (cols, '(a,i0,a,i0)') 'columns ', c1, '-', c2
        s = me%where(i)//', '//trim(cols)//' ('//trim(me%key(i))//' card, field F'// &
            achar(48 + f)//' '''//what//''')'
    end function context

    !> Real number from field f of line i, in [lo, hi]; a blank field takes
    !! `default` when present and is an error otherwise.
    subroutine reader_real(me, i, f, what, units, v, lo, hi, default)
        class(deck_reader_t), intent(inout) :: me
        integer, intent(in) :: i, f
        character(len=*), intent(in) :: what, units
        real(wp), intent(out) :: v
        real(wp), intent(in) :: lo, hi
        real(wp), intent(in), optional :: default
        character(len=10) :: s
        character(len=60) :: range
        logical :: ok
        v = 0.0_wp
        if (me%failed()) return
        s = me%raw(i, f)
        if (len_trim(s) == 0) then
            if (present(default)) then
                v = default
            else
                call me%fail(context(me, i, f, what)//': found a blank field; expected a real number ['// &
                             units//']')
            end if
            return
        end if
        call parse_real(s, v, ok)
        if (.not. ok) then
            call me%fail(context(me, i, f, what)//': found "'//trim(s)//'"; expected a real number ['// &
                         units//'] such as 1.5, -2 or 3.0E-4')
            return
        end if
        if (.not. (v >= lo .and. v <= hi)) then
            write (range, '(a,es10.3,a,es10.3,a)') '[', lo, ', ', hi, ']'
            call me%fail(context(me, i, f, what)//': found '//trim(s)//'; expected a value in '// &
                         trim(range)//' '//units)
        end if
    end subroutine reader_real

    !> Integer from field f of line i, in [lo, hi].
    subroutine reader_int(me, i, f, what, v, lo, hi, default)
        class(deck_reader_t), intent(inout) :: me
        integer, intent(in) :: i, f
        character(len=*), intent(in) :: what
        integer, intent(out) :: v
        integer, intent(in) :: lo, hi
        integer, intent(in), optional :: default
        character(len=10) :: s
        character(len=60) :: range
        integer :: k, ios
        v = 0
        if (me%failed()) return
        s = me%raw(i, f)
        if (len_trim(s) == 0) then
            if (present(default)) then
                v = default
            else
                call me%fail(context(me, i, f, what)//': found a blank field; expected an integer')
            end if
            return
        end if
        do k = 1, len_trim(s)
            if (index('0123456789', s(k:k)) == 0 .and. .not. (k == 1 .and. index('+-', s(k:k)) > 0)) then
                call me%fail(context(me, i, f, what)//': found "'//trim(s)//'"; expected an integer')
                return
            end if
        end do
        read (s, *, iostat=ios) v
        if (ios /= 0 .or. v < lo .or. v > hi) then
            write (range, '(a,i0,a,i0,a)') '[', lo, ', ', hi, ']'
            call me%fail(context(me, i, f, what)//': found '//trim(s)//'; expected an integer in '//trim(range))
        end if
    end subroutine reader_int

    !> Name (letters, digits, _ - .) from field f, upper case; blank allowed
    !! only when `optional_blank` is true.
    subroutine reader_name(me, i, f, what, v, optional_blank)
        class(deck_reader_t), intent(inout) :: me
        integer, intent(in) :: i, f
        character(len=*), intent(in) :: what
        character(len=*), intent(out) :: v
        logical, intent(in), optional :: optional_blank
        character(len=10) :: s
        integer :: k
        v = ''
        if (me%failed()) return
        s = upper(me%raw(i, f))
        if (len_trim(s) == 0) then
            if (present(optional_blank)) then
                if (optional_blank) return
            end if
            call me%fail(context(me, i, f, what)//': found a blank field; expected a name')
            return
        end if
        do k = 1, len_trim(s)
            if (index('ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.', s(k:k)) == 0) then
                call me%fail(context(me, i, f, what)//': found "'//trim(s)// &
                             '"; expected a name of letters, digits, _ - . without spaces')
                return
            end if
        end do
        v = s
    end subroutine reader_name

    !> Free text of columns c1..80 of line i.
    function reader_text(me, i, c1) result(s)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i, c1
        character(len=:), allocatable :: s
        s = trim(adjustl(me%lines(i)%text(c1:80)))
    end function reader_text

    !> Strict real syntax: [sign] digits [. digits] | [sign] . digits, then an
    !! optional exponent (E or D) [sign] digits. Rejects NaN, Inf, commas.
    subroutine parse_real(s, v, ok)
        character(len=*), intent(in) :: s
        real(wp), intent(out) :: v
        logical, intent(out) :: ok
        character(len=len(s)) :: t
        integer :: k, n, nd, ios
        logical :: seen_dot
        t = upper(trim(s))
        n = len_trim(t)
        ok = .false.
        v = 0.0_wp
        k = 1
        if (index('+-', t(k:k)) > 0) k = k + 1
        nd = 0; seen_dot = .false.
        do while (k <= n)
            if (index('0123456789', t(k:k)) > 0) then
                nd = nd + 1
            else if (t(k:k) == '.' .and. .not. seen_dot) then
                seen_dot = .true.
            else
                exit
            end if
            k = k + 1
        end do
        if (nd == 0) return
        if (k <= n) then
            if (t(k:k) /= 'E' .and. t(k:k) /= 'D') return
            t(k:k) = 'E'
            k = k + 1
            if (k <= n) then
                if (index('+-', t(k:k)) > 0) k = k + 1
            end if
            if (k > n) return
            do while (k <= n)
                if (index('0123456789', t(k:k)) == 0) return
                k = k + 1
            end do
        end if
        read (t(1:n), *, iostat=ios) v
        if (ios /= 0) return
        ok = abs(v) <= huge(v)
    end subroutine parse_real

    !> Upper-case copy of a string.
    pure function upper(s) result(u)
        character(len=*), intent(in) :: s
        character(len=len(s)) :: u
        integer :: k, c
        u = s
        do k = 1, len(s)
            c = iachar(s(k:k))
            if (c >= 97 .and. c <= 122) u(k:k) = achar(c - 32)
        end do
    end function upper

    !> Whole contents of a file (or /dev/stdin) as bytes; stat /= 0 with a
    !! message when it cannot be opened or read.
    subroutine read_bytes(path, bytes, stat, errmsg)
        character(len=*), intent(in) :: path
        character(len=:), allocatable, intent(out) :: bytes
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: u, n, cap
        integer(i8) :: sz
        character(len=1) :: c
        character(len=:), allocatable :: tmp
        errmsg = ''
        open (newunit=u, file=path, access='stream', form='unformatted', action='read', status='old', &
              iostat=stat, iomsg=errmsg)
        if (stat /= 0) return
        inquire (unit=u, size=sz)
        if (sz > 0) then
            allocate (character(len=int(sz)) :: bytes)
            read (u, iostat=stat, iomsg=errmsg) bytes
        else
            ! a pipe: size unknown, read byte by byte
            cap = 65536
            allocate (character(len=cap) :: bytes)
            n = 0
            do
                read (u, iostat=stat) c
                if (stat /= 0) exit
                n = n + 1
                if (n > cap) then
                    tmp = bytes
                    cap = 2*cap
                    deallocate (bytes)
                    allocate (character(len=cap) :: bytes)
                    bytes(1:n - 1) = tmp(1:n - 1)
                end if
                bytes(n:n) = c
            end do
            bytes = bytes(1:n)
            if (is_iostat_end(stat)) stat = 0
        end if
        close (u)
    end subroutine read_bytes

    !> Read all card images of file `path` (named `source` in messages),
    !! expanding INCLUDE cards and checking every line: at most 80 columns,
    !! printable ASCII, no tab; CR LF line ends read as LF, a carriage
    !! return anywhere else is an error.
    recursive subroutine read_card_images(me, path, source, depth)
        class(deck_reader_t), intent(inout) :: me
        character(len=*), intent(in) :: path, source
        integer, intent(in) :: depth
        character(len=:), allocatable :: bytes, line
        character(len=path_len) :: incpath
        character(len=msglen) :: iomsg
        integer :: ios, lineno, k, c, p0, p1, n
        logical :: exists

        call read_bytes(path, bytes, ios, iomsg)
        if (ios /= 0) then
            call me%fail(source//': cannot be read ('//trim(iomsg)//')')
            return
        end if
        lineno = 0
        p0 = 1
        do while (p0 <= len(bytes))
            if (me%failed()) return
            p1 = index(bytes(p0:), achar(10))
            if (p1 == 0) then
                p1 = len(bytes) + 1
            else
                p1 = p0 + p1 - 1
            end if
            line = bytes(p0:p1 - 1)
            p0 = p1 + 1
            lineno = lineno + 1
            n = len(line)
            if (n > 0) then
                if (line(n:n) == achar(13)) n = n - 1      ! CR LF
            end if
            do k = 1, n
                c = iachar(line(k:k))
                if (c == 9) then
                    call me%fail(source//' line '//trim(int_str(lineno))//', column '//trim(int_str(k))// &
                                 ': found a tab character; card images use spaces so that columns are exact')
                    return
                else if (c == 13) then
                    call me%fail(source//' line '//trim(int_str(lineno))//', column '//trim(int_str(k))// &
                                 ': found a carriage return inside the card; expected plain text')
                    return
                else if (c < 32 .or. c > 126) then
                    call me%fail(source//' line '//trim(int_str(lineno))//', column '//trim(int_str(k))// &
                                 ': found a non-printable or non-ASCII character; expected plain ASCII text')
                    return
                end if
            end do
            if (len_trim(line(1:n)) > 80) then
                call me%fail(source//' line '//trim(int_str(lineno))//', columns 81-'// &
                             trim(int_str(len_trim(line(1:n))))// &
                             ': found text beyond column 80; card images have 80 columns')
                return
            end if
            if (len_trim(line(1:n)) == 0) cycle
            if (line(1:1) == '*') cycle
            if (upper(line(1:min(n, 8))) == 'INCLUDE') then
                incpath = ''
                if (n >= 11) incpath = adjustl(line(11:n))
                if (len_trim(incpath) == 0) then
                    call me%fail(source//' line '//trim(int_str(lineno))// &
                                 ', columns 11-80 (INCLUDE card): found no file name; expected the path of a deck file')
                    return
                end if
                if (depth >= max_include_depth) then
                    call me%fail(source//' line '//trim(int_str(lineno))// &
                                 ' (INCLUDE card): includes nested too deeply (more than 4 levels; a loop?)')
                    return
                end if
                inquire (file=trim(incpath), exist=exists)
                if (.not. exists) then
                    call me%fail(source//' line '//trim(int_str(lineno))//', columns 11-80 (INCLUDE card): file "'// &
                                 trim(incpath)//'" not found (paths are relative to the working directory)')
                    return
                end if
                call read_card_images(me, trim(incpath), trim(incpath), depth + 1)
                cycle
            end if
            call append_line(me, line(1:n), source, lineno)
        end do
    end subroutine read_card_images

    subroutine append_line(me, text, source, lineno)
        class(deck_reader_t), intent(inout) :: me
        character(len=*), intent(in) :: text, source
        integer, intent(in) :: lineno
        type(deck_line_t), allocatable :: tmp(:)
        if (.not. allocated(me%lines)) allocate (me%lines(64))
        if (me%nlines == size(me%lines)) then
            allocate (tmp(2*size(me%lines)))
            tmp(1:me%nlines) = me%lines(1:me%nlines)
            call move_alloc(tmp, me%lines)
        end if
        me%nlines = me%nlines + 1
        me%lines(me%nlines)%text = text
        me%lines(me%nlines)%source = source
        me%lines(me%nlines)%line = lineno
    end subroutine append_line

    pure function int_str(i) result(s)
        integer, intent(in) :: i
        character(len=16) :: s
        write (s, '(i0)') i
    end function int_str

end module hn_deck_reader
