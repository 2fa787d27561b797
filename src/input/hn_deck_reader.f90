!> Reading card images: lines from standard input and INCLUDE files, the
!! fixed columns of a card, and strict conversion of fields with errors
!! that name the source, line, columns, card, field, what was found and
!! what was expected.
!!
!! Card layout (80 columns): columns 1-8 the card name, 9-10 blank, then
!! seven fields of ten columns: F1 = 11-20, F2 = 21-30, ... F7 = 71-80.
!! A card whose columns 1-10 are blank continues the card above it.
!! A number stays inside its field: a field read as a number whose text
!! touches the next (or previous) field's text, a digit or point against
!! a digit, sign or point with no blank between, or that joins with it into
!! one number, is an error naming both fields (`separated`); a field in the
!! form the program writes into ten columns (`field_text`, CHANGE cards and
!! sweeps) is whole.
!! '*' in column 1 marks a comment; blank lines are ignored. CR LF line ends
!! read as LF line ends; a carriage return anywhere else is an error.
!!
!! Input is bounded: only regular files are read as INCLUDE targets, and
!! standard input only when it is a regular file or a pipe (a device or a
!! directory never ends or cannot be read); the deck as a whole has at most
!! max_deck_bytes bytes, max_deck_lines lines and max_card_images card
!! images. An INCLUDE path is looked for relative to the including file,
!! then the working directory, then each directory of the include path.
module hn_deck_reader
    use hn_kinds, only: wp, msglen, i8
    use hn_strings, only: int_str, upper, parse_real, field_text, field_value
    use hn_status, only: stat_bad_input
    use hn_posix, only: file_kind, stdin_kind, kind_name, kind_missing, kind_regular, kind_directory, kind_fifo, kind_socket, &
                        parent_directory, is_absolute, join_path, read_stdin_block
    implicit none
    private

    public :: deck_line_t, deck_reader_t, read_card_images, field_columns, int_str, upper, parse_real
    public :: field_text, field_value, locate_field, read_data_file, next_line, add_environment_path

    integer, parameter, public :: path_len = 256   !! longest file path

    !> One card image as read, with where it came from.
    type :: deck_line_t
        character(len=80) :: text = ''
        character(len=:), allocatable :: source  !! 'stdin' or the included file
        integer :: line = 0                      !! line number in that source
        integer :: via = 0                       !! which INCLUDE brought it in (0: the deck itself)
    end type deck_line_t

    integer, parameter, public :: nfields = 7
    integer, parameter :: max_include_depth = 4
    integer(i8), parameter, public :: max_deck_bytes = 64_i8*1024*1024   !! all files of a deck together
    integer, parameter, public :: max_deck_lines = 1000000               !! lines read, comments included
    integer, parameter, public :: max_card_images = 500000               !! card images kept
    character(len=*), parameter, public :: stdin_path = '/dev/stdin'    !! path that means standard input

    !> The card images of a deck and the first error met while reading them.
    type :: deck_reader_t
        type(deck_line_t), allocatable :: lines(:)
        integer :: nlines = 0
        character(len=:), allocatable :: top   !! name of the deck itself in messages
        integer :: stat = 0
        character(len=msglen) :: errmsg = ''
        character(len=path_len), allocatable :: search(:)  !! include path: directories searched for INCLUDE files
        character(len=msglen), allocatable :: vias(:)      !! " (included from ...)" of each INCLUDE read
        integer :: nvias = 0
        integer(i8) :: nbytes = 0     !! bytes read so far (all files)
        integer :: nphysical = 0      !! lines read so far (all files, comments included)
    contains
        procedure :: failed => reader_failed
        procedure :: fail => reader_fail
        procedure :: key => reader_key
        procedure :: raw => reader_raw
        procedure :: is_blank => reader_is_blank
        procedure :: real => reader_real
        procedure :: int => reader_int
        procedure :: name => reader_name
        procedure :: choice => reader_choice
        procedure :: text => reader_text
        procedure :: where => reader_where
        procedure :: context
        procedure :: separated => reader_separated
        procedure :: read_data_file
        procedure :: find_file => resolve_include
    end type deck_reader_t

contains

    !> First and last column of field f (1..7).
    pure subroutine field_columns(f, c1, c2)
        integer, intent(in) :: f     !! field number, 1..nfields (F1..F7)
        integer, intent(out) :: c1   !! its first column (11 for F1)
        integer, intent(out) :: c2   !! its last column (c1 + 9)
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
        character(len=*), intent(in) :: msg   !! the whole message (context, found, expected)
        if (me%stat /= 0) return
        me%stat = stat_bad_input
        me%errmsg = msg
    end subroutine reader_fail

    !> "stdin line 12" for deck line i; a line of an included file adds
    !! where it was included: "a.inp line 3 (included from stdin line 12)";
    !! a card image of a command-line option: "--change 2".
    function reader_where(me, i) result(s)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i   !! card image number
        character(len=:), allocatable :: s
        if (len(me%lines(i)%source) > 2) then
            if (me%lines(i)%source(1:2) == '--') then
                ! a card image given on the command line: "--change 2"
                s = me%lines(i)%source//' '//trim(int_str(me%lines(i)%line))
                return
            end if
        end if
        s = me%lines(i)%source//' line '//trim(int_str(me%lines(i)%line))
        if (allocated(me%vias) .and. me%lines(i)%via > 0) then
            if (me%lines(i)%via <= me%nvias) s = s//trim(me%vias(me%lines(i)%via))
        end if
    end function reader_where

    !> Card name of line i (columns 1-8, upper case).
    function reader_key(me, i) result(k)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i   !! card image number
        character(len=8) :: k
        k = upper(me%lines(i)%text(1:8))
    end function reader_key

    !> Raw text of field f of line i, adjusted left.
    function reader_raw(me, i, f) result(s)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i   !! card image number
        integer, intent(in) :: f   !! field number, 1..nfields
        character(len=10) :: s
        integer :: c1, c2
        call field_columns(f, c1, c2)
        s = adjustl(me%lines(i)%text(c1:c2))
    end function reader_raw

    logical function reader_is_blank(me, i, f)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i   !! card image number
        integer, intent(in) :: f   !! field number, 1..nfields
        reader_is_blank = len_trim(me%raw(i, f)) == 0
    end function reader_is_blank

    !> Context of an error in field f of line i: "stdin line 4, columns
    !! 31-40 (BODY card, field F3 'mass')"; on a continuation card "(TABLE
    !! card continuation 3, field F1 'time')".
    function context(me, i, f, what) result(s)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i               !! card image number
        integer, intent(in) :: f               !! field number, 1..nfields
        character(len=*), intent(in) :: what   !! what the field holds, as in the card's documentation
        character(len=:), allocatable :: s
        character(len=40) :: cols
        integer :: c1, c2, j
        call field_columns(f, c1, c2)
        write (cols, '(a,i0,a,i0)') 'columns ', c1, '-', c2
        if (len_trim(me%key(i)) > 0) then
            s = me%where(i)//', '//trim(cols)//' ('//trim(me%key(i))//' card, field F'// &
                achar(48 + f)//' '''//what//''')'
        else
            ! a continuation card: name the card it continues
            j = i
            do while (j > 1)
                if (len_trim(me%lines(j)%text(1:10)) > 0) exit
                j = j - 1
            end do
            s = me%where(i)//', '//trim(cols)//' ('//trim(me%key(j))//' card continuation '// &
                trim(int_str(i - j))//', field F'//achar(48 + f)//' '''//what//''')'
        end if
    end function context

    !> Field f of card image i kept apart from its neighbours: when the text
    !! of F(f-1)/Ff or Ff/F(f+1) runs across their boundary with no blank
    !! between (a digit or point against a digit, sign or point, or two
    !! pieces that join into one number), a located error naming both fields
    !! and the columns the number spills into: `12.5` over the F3/F4
    !! boundary would otherwise read as 12 and 0.5. A field in the form
    !! `field_text` writes (ten columns, CHANGE cards and sweeps) is whole.
    subroutine reader_separated(me, i, f, what)
        class(deck_reader_t), intent(inout) :: me
        integer, intent(in) :: i               !! card image number
        integer, intent(in) :: f               !! field number, 1..nfields
        character(len=*), intent(in) :: what   !! what field f holds (named in messages)
        integer :: g
        if (me%failed()) return
        do g = f - 1, f
            if (g < 1 .or. g >= nfields) cycle
            call boundary(g)
            if (me%failed()) return
        end do
    contains
        !> The boundary between fields g and g + 1.
        subroutine boundary(g)
            integer, intent(in) :: g
            character(len=80) :: t
            character(len=:), allocatable :: token, fields, spill
            integer :: c, a, b
            real(wp) :: v
            logical :: ok
            t = me%lines(i)%text
            c = 10*g + 10                      ! the last column of field g
            if (t(c:c) == ' ' .or. t(c + 1:c + 1) == ' ') return
            a = c
            do while (a > 10*g + 1)
                if (t(a - 1:a - 1) == ' ') exit
                a = a - 1
            end do
            b = c + 1
            do while (b < c + 10)
                if (t(b + 1:b + 1) == ' ') exit
                b = b + 1
            end do
            token = t(a:b)
            call parse_real(token, v, ok)
            if (.not. ok .and. .not. (index('0123456789.', t(c:c)) > 0 .and. &
                                      index('0123456789.+-', t(c + 1:c + 1)) > 0)) return
            if (whole_field(t(c - 9:c)) .or. whole_field(t(c + 1:c + 10))) return
            ! the number belongs to the field holding most of it, and spills into the other
            if (c - a + 1 >= b - c) then
                spill = 'columns '//trim(int_str(c + 1))//'-'//trim(int_str(b))//' of F'//achar(49 + g)
            else
                spill = 'columns '//trim(int_str(a))//'-'//trim(int_str(c))//' of F'//achar(48 + g)
            end if
            if (g == f) then
                fields = 'fields F'//achar(48 + g)//' '''//what//''' and F'//achar(49 + g)
            else
                fields = 'fields F'//achar(48 + g)//' and F'//achar(49 + g)//' '''//what//''''
            end if
            call me%fail(me%where(i)//', columns '//trim(int_str(a))//'-'//trim(int_str(b))//' ('// &
                         card_name(me, i)//', '//fields//'): found "'//token//'" across the boundary of F'// &
                         achar(48 + g)//' (columns '//trim(int_str(c - 9))//'-'//trim(int_str(c))//') and F'// &
                         achar(49 + g)//' (columns '//trim(int_str(c + 1))//'-'//trim(int_str(c + 10))// &
                         ') with no blank between: the number spills into '//spill// &
                         '; expected each number inside its own field''s ten columns')
        end subroutine boundary
    end subroutine reader_separated

    !> A field's ten columns all filled in the form field_text writes (a
    !! value put there by a CHANGE card or a sweep): a whole field.
    logical function whole_field(s)
        character(len=10), intent(in) :: s   !! the field's columns
        real(wp) :: v
        logical :: ok
        whole_field = .false.
        if (index(s, ' ') > 0) return
        call parse_real(s, v, ok)
        if (ok) whole_field = field_text(v) == s
    end function whole_field

    !> "BODY card", or "TABLE card continuation 3" for a continuation card.
    function card_name(me, i) result(s)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i   !! card image number
        character(len=:), allocatable :: s
        integer :: j
        if (len_trim(me%key(i)) > 0) then
            s = trim(me%key(i))//' card'
            return
        end if
        j = i
        do while (j > 1)
            if (len_trim(me%lines(j)%text(1:10)) > 0) exit
            j = j - 1
        end do
        s = trim(me%key(j))//' card continuation '//trim(int_str(i - j))
    end function card_name

    !> Real number from field f of line i, in [lo, hi]; a blank field takes
    !! `default` when present and is an error otherwise.
    subroutine reader_real(me, i, f, what, units, v, lo, hi, default)
        class(deck_reader_t), intent(inout) :: me
        integer, intent(in) :: i                    !! card image number
        integer, intent(in) :: f                    !! field number, 1..nfields
        character(len=*), intent(in) :: what        !! what the field holds (named in messages)
        character(len=*), intent(in) :: units       !! its units (named in messages)
        real(wp), intent(out) :: v                  !! the value (0 on an error)
        real(wp), intent(in) :: lo                  !! smallest value accepted
        real(wp), intent(in) :: hi                  !! largest value accepted
        real(wp), intent(in), optional :: default   !! value of a blank field (absent: blank is an error)
        character(len=10) :: s
        character(len=60) :: range
        character(len=10) :: why
        logical :: ok
        v = 0.0_wp
        if (me%failed()) return
        call me%separated(i, f, what)
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
        call parse_real(s, v, ok, why)
        if (.not. ok) then
            select case (trim(why))
            case ('overflow')
                call me%fail(context(me, i, f, what)//': found "'//trim(s)//'", beyond the range of double '// &
                             'precision (about 1.8E+308); expected a real number ['//units//'] of a usable size')
            case ('underflow')
                call me%fail(context(me, i, f, what)//': found "'//trim(s)//'", too small for double precision '// &
                             '(it would become zero); expected 0 or a real number ['//units//'] of a usable size')
            case default
                call me%fail(context(me, i, f, what)//': found "'//trim(s)//'"; expected a real number ['// &
                             units//'] such as 1.5, -2 or 3.0E-4')
            end select
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
        integer, intent(in) :: i                   !! card image number
        integer, intent(in) :: f                   !! field number, 1..nfields
        character(len=*), intent(in) :: what       !! what the field holds (named in messages)
        integer, intent(out) :: v                  !! the value (0 on an error)
        integer, intent(in) :: lo                  !! smallest value accepted
        integer, intent(in) :: hi                  !! largest value accepted
        integer, intent(in), optional :: default   !! value of a blank field (absent: blank is an error)
        character(len=10) :: s
        character(len=60) :: range
        integer :: k, ios
        v = 0
        if (me%failed()) return
        call me%separated(i, f, what)
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
        integer, intent(in) :: i                          !! card image number
        integer, intent(in) :: f                          !! field number, 1..nfields
        character(len=*), intent(in) :: what              !! what the field holds (named in messages)
        character(len=*), intent(out) :: v                !! the name, upper case ('' on an error or when blank)
        logical, intent(in), optional :: optional_blank   !! a blank field is allowed (default: no)
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

    !> A name that must be one of `choices`: refused with the located
    !! message 'found "X"; expected A, B or C' otherwise.
    subroutine reader_choice(me, i, f, what, choices, v)
        class(deck_reader_t), intent(inout) :: me
        integer, intent(in) :: i                      !! card image number
        integer, intent(in) :: f                      !! field number, 1..nfields
        character(len=*), intent(in) :: what          !! what the field holds (named in messages)
        character(len=*), intent(in) :: choices(:)    !! the allowed names, upper case
        character(len=*), intent(out) :: v            !! the name ('' on an error)
        character(len=:), allocatable :: expected
        integer :: k
        call me%name(i, f, what, v)
        if (me%failed() .or. any(choices == v)) return
        expected = trim(choices(1))
        do k = 2, size(choices)
            expected = expected//merge(' or ', ',   ', k == size(choices))
            expected = trim(expected)//' '//trim(choices(k))
        end do
        call me%fail(context(me, i, f, what)//': found "'//trim(v)//'"; expected '//expected)
        v = ''
    end subroutine reader_choice

    !> Free text of columns c1..80 of line i.
    function reader_text(me, i, c1) result(s)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i    !! card image number
        integer, intent(in) :: c1   !! first column of the text
        character(len=:), allocatable :: s
        s = trim(adjustl(me%lines(i)%text(c1:80)))
    end function reader_text

    !> Whole contents of a regular file, or of standard input when `path` is
    !! stdin_path, as bytes; at most `budget` bytes. stat /= 0 with a message
    !! (what the file is, and why it is not read) otherwise.
    subroutine read_bytes(path, budget, bytes, stat, errmsg)
        character(len=*), intent(in) :: path
        integer(i8), intent(in) :: budget
        character(len=:), allocatable, intent(out) :: bytes
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        integer :: u, kind
        integer(i8) :: sz
        errmsg = ''
        stat = 1
        if (path == stdin_path) then
            kind = stdin_kind()
            if (kind == kind_fifo .or. kind == kind_socket) then
                call read_pipe(budget, bytes, stat, errmsg)
                return
            end if
            if (kind /= kind_regular) then
                errmsg = 'standard input is '//kind_name(kind)//', which '//trim(why_not(kind))// &
                         '; expected a deck file (hhneck DECK or hhneck < DECK)'
                return
            end if
        else
            kind = file_kind(path)
            if (kind == kind_missing) then
                errmsg = 'file not found'
                return
            end if
            if (kind /= kind_regular) then
                errmsg = 'it is '//kind_name(kind)//', which '//trim(why_not(kind))//'; expected a regular deck file'
                return
            end if
        end if
        open (newunit=u, file=path, access='stream', form='unformatted', action='read', status='old', &
              iostat=stat, iomsg=errmsg)
        if (stat /= 0) return
        inquire (unit=u, size=sz)
        if (sz > budget) then
            stat = 1
            write (errmsg, '(a,i0,a,i0,a)') 'it has ', sz, ' bytes, more than the ', budget, &
                ' bytes left of the limit on a deck (docs/errors.md)'
        else if (sz > 0) then
            allocate (character(len=int(sz)) :: bytes)
            read (u, iostat=stat, iomsg=errmsg) bytes
        else
            bytes = ''
        end if
        close (u)
    end subroutine read_bytes

    !> Why a file of this kind is not read as a deck.
    pure function why_not(kind) result(s)
        integer, intent(in) :: kind
        character(len=60) :: s
        select case (kind)
        case (kind_missing); s = 'is closed'
        case (kind_fifo); s = 'may never end or block for a writer'
        case (kind_regular); s = 'can be read'
        case default
            s = 'cannot be read as text or never ends'
            if (kind == 2) s = 'cannot be read as text'
        end select
    end function why_not

    !> Standard input from a pipe, in blocks, up to `budget` bytes.
    subroutine read_pipe(budget, bytes, stat, errmsg)
        integer(i8), intent(in) :: budget
        character(len=:), allocatable, intent(out) :: bytes
        integer, intent(out) :: stat
        character(len=*), intent(out) :: errmsg
        character(len=:), allocatable :: tmp
        integer(i8) :: n, got
        integer, parameter :: blk = 1048576
        allocate (character(len=blk) :: bytes)
        n = 0
        stat = 0
        errmsg = ''
        do
            if (n + blk > len(bytes, kind=i8)) then
                allocate (character(len=int(min(2*len(bytes, kind=i8), budget + blk))) :: tmp)
                tmp(1:n) = bytes(1:n)
                call move_alloc(tmp, bytes)
            end if
            call read_stdin_block(bytes(n + 1:n + blk), got)
            if (got < 0) then
                stat = 1
                errmsg = 'standard input could not be read'
                return
            end if
            if (got == 0) exit
            n = n + got
            if (n > budget) then
                stat = 1
                write (errmsg, '(a,i0,a)') 'standard input goes on beyond ', budget, &
                    ' bytes, the limit on a deck (docs/errors.md); expected a deck that ends'
                return
            end if
        end do
        bytes = bytes(1:n)
    end subroutine read_pipe

    !> Read all card images of file `path` (stdin_path for standard input,
    !! named `source` in messages), expanding INCLUDE cards.
    subroutine read_card_images(me, path, source, depth)
        class(deck_reader_t), intent(inout) :: me
        character(len=*), intent(in) :: path     !! file to read, or stdin_path
        character(len=*), intent(in) :: source   !! its name in messages ('stdin' or the file name)
        integer, intent(in), optional :: depth   !! unused (kept for callers that pass 0)
        character(len=:), allocatable :: bytes
        character(len=msglen) :: iomsg
        integer :: ios
        call read_bytes(path, max_deck_bytes - me%nbytes, bytes, ios, iomsg)
        if (ios /= 0) then
            if (path == stdin_path) then
                call me%fail(trim(iomsg))
            else
                call me%fail(source//': cannot be read: '//trim(iomsg))
            end if
            return
        end if
        me%nbytes = me%nbytes + len(bytes, kind=i8)
        call scan_lines(me, bytes, path, source, 0, '')
        if (present(depth)) continue
    end subroutine read_card_images

    !> The lines of one file (its bytes read): checked, INCLUDE cards
    !! expanded, card images kept. Every line must have at most 80 columns,
    !! printable ASCII, no tab; CR LF line ends read as LF, a carriage return
    !! anywhere else is an error. `via` (" (included from ...)") is added to
    !! the place of every error in this file.
    recursive subroutine scan_lines(me, bytes, path, source, depth, via)
        class(deck_reader_t), intent(inout) :: me
        character(len=*), intent(in) :: bytes, path, source, via
        integer, intent(in) :: depth
        character(len=:), allocatable :: line, incfile, incbytes
        character(len=path_len) :: incname
        character(len=msglen) :: iomsg
        integer :: ios, lineno, k, c, p0, n, ivia

        ivia = 0
        if (len(via) > 0) then
            call add_via(me, via)
            ivia = me%nvias
        end if
        lineno = 0
        p0 = 1
        do while (p0 <= len(bytes))
            if (me%failed()) return
            call next_line(bytes, p0, line)
            lineno = lineno + 1
            me%nphysical = me%nphysical + 1
            if (me%nphysical > max_deck_lines) then
                call me%fail(at(lineno)//': the deck has more than '//trim(int_str(max_deck_lines))// &
                             ' lines (comments included), the limit on a deck (docs/errors.md)')
                return
            end if
            n = len(line)
            if (n > 0) then
                if (line(n:n) == achar(13)) n = n - 1      ! CR LF
            end if
            do k = 1, n
                c = iachar(line(k:k))
                if (c >= 32 .and. c <= 126) cycle
                if (c == 9) then
                    call me%fail(at(lineno)//', column '//trim(int_str(k))// &
                                 ': found a tab character; card images use spaces so that columns are exact')
                else if (c == 13) then
                    call me%fail(at(lineno)//', column '//trim(int_str(k))// &
                                 ': found a carriage return inside the card; expected plain text')
                else
                    call me%fail(at(lineno)//', column '//trim(int_str(k))// &
                                 ': found a non-printable or non-ASCII character; expected plain ASCII text')
                end if
                return
            end do
            if (len_trim(line(1:n)) > 80) then
                call me%fail(at(lineno)//', columns 81-'//trim(int_str(len_trim(line(1:n))))// &
                             ': found text beyond column 80; card images have 80 columns')
                return
            end if
            if (len_trim(line(1:n)) == 0) cycle
            if (line(1:1) == '*') cycle
            if (upper(line(1:min(n, 8))) == 'INCLUDE') then
                incname = ''
                if (n >= 11) incname = adjustl(line(11:n))
                if (len_trim(incname) == 0) then
                    call me%fail(at(lineno)//', columns 11-80 (INCLUDE card): found no file name; '// &
                                 'expected the path of a deck file')
                    return
                end if
                if (depth >= max_include_depth) then
                    call me%fail(at(lineno)//' (INCLUDE card): includes nested too deeply (more than '// &
                                 trim(int_str(max_include_depth))//' levels; a loop?)')
                    return
                end if
                call resolve_include(me, trim(incname), path, incfile, iomsg)
                if (len(incfile) > 0) then
                    call read_bytes(incfile, max_deck_bytes - me%nbytes, incbytes, ios, iomsg)
                    if (ios /= 0) iomsg = '"'//trim(incname)//'" cannot be read: '//iomsg
                end if
                if (len(incfile) == 0 .or. ios /= 0) then
                    call me%fail(at(lineno)//', columns 11-80 (INCLUDE card): '//trim(iomsg))
                    return
                end if
                me%nbytes = me%nbytes + len(incbytes, kind=i8)
                call scan_lines(me, incbytes, incfile, incfile, depth + 1, &
                                ' (included from '//source//' line '//trim(int_str(lineno))//via//')')
                cycle
            end if
            if (me%nlines >= max_card_images) then
                call me%fail(at(lineno)//': the deck has more than '//trim(int_str(max_card_images))// &
                             ' card images, the limit on a deck (docs/errors.md)')
                return
            end if
            call append_line(me, line(1:n), source, lineno, ivia)
        end do
    contains
        !> "source line N" with where this file was included.
        function at(ln) result(s)
            integer, intent(in) :: ln
            character(len=:), allocatable :: s
            s = source//' line '//trim(int_str(ln))//via
        end function at
    end subroutine scan_lines

    !> The file an INCLUDE card names: an absolute path as it is; a relative
    !! one looked for next to the including file, then in the working
    !! directory, then in each directory of the include path. `found` is ''
    !! with a message when there is no such regular file (no such directory,
    !! with `directory`: a calibration deck's DATA directory).
    subroutine resolve_include(me, name, including, found, errmsg, directory)
        class(deck_reader_t), intent(in) :: me
        character(len=*), intent(in) :: name                  !! the path as written on the card
        character(len=*), intent(in) :: including             !! the file holding the card (stdin_path: none)
        character(len=:), allocatable, intent(out) :: found   !! where it was found ('' when not)
        character(len=*), intent(out) :: errmsg               !! why not ('' when found)
        logical, intent(in), optional :: directory            !! look for a directory instead of a file
        character(len=:), allocatable :: tried
        integer :: k, kind, wanted
        wanted = kind_regular
        if (present(directory)) then
            if (directory) wanted = kind_directory
        end if
        found = ''
        errmsg = ''
        tried = ''
        if (is_absolute(name)) then
            call try(name)
        else
            if (including /= stdin_path .and. len(parent_directory(including)) > 0) &
                call try(join_path(parent_directory(including), name))
            if (len(found) == 0 .and. len_trim(errmsg) == 0) call try(name)
            if (allocated(me%search)) then
                do k = 1, size(me%search)
                    if (len(found) > 0 .or. len_trim(errmsg) > 0) exit
                    if (len_trim(me%search(k)) > 0) call try(join_path(me%search(k), name))
                end do
            end if
        end if
        if (len(found) == 0 .and. len_trim(errmsg) == 0) &
            errmsg = trim(merge('file     ', 'directory', wanted == kind_regular))//' "'//name// &
                     '" not found (looked for '//tried//'; an installed hhneck finds '// &
                     'shipped decks through -I DIR or HHNECK_PATH)'
    contains
        subroutine try(p)
            character(len=*), intent(in) :: p
            if (len(found) > 0 .or. len_trim(errmsg) > 0) return
            if (index(', '//tried//', ', ', '//p//', ') > 0) return     ! the same place twice
            if (len(tried) > 0) tried = tried//', '
            tried = tried//p
            kind = file_kind(p)
            if (kind == wanted) then
                found = p
            else if (kind /= kind_missing .and. wanted == kind_directory) then
                errmsg = '"'//p//'" is '//kind_name(kind)//'; expected a directory'
            else if (kind /= kind_missing) then
                errmsg = '"'//p//'" is '//kind_name(kind)//', which '//trim(why_not(kind))// &
                         '; expected a regular deck file'
            end if
        end subroutine try
    end subroutine resolve_include

    !> Remember the " (included from ...)" of an INCLUDE read.
    subroutine add_via(me, via)
        class(deck_reader_t), intent(inout) :: me
        character(len=*), intent(in) :: via
        character(len=msglen), allocatable :: tmp(:)
        if (.not. allocated(me%vias)) allocate (me%vias(8))
        if (me%nvias == size(me%vias)) then
            allocate (tmp(2*size(me%vias)))
            tmp(1:me%nvias) = me%vias(1:me%nvias)
            call move_alloc(tmp, me%vias)
        end if
        me%nvias = me%nvias + 1
        me%vias(me%nvias) = via
    end subroutine add_via

    subroutine append_line(me, text, source, lineno, via)
        class(deck_reader_t), intent(inout) :: me
        character(len=*), intent(in) :: text, source
        integer, intent(in) :: lineno, via
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
        me%lines(me%nlines)%via = via
    end subroutine append_line

    !> The line of `text` that starts at position p, without its line feed;
    !! p moves to the start of the next line (beyond len(text) after the last).
    pure subroutine next_line(text, p, line)
        character(len=*), intent(in) :: text                 !! text of lines ended by LF
        integer, intent(inout) :: p                          !! start of the line; then of the next one
        character(len=:), allocatable, intent(out) :: line   !! the line
        integer :: q
        q = index(text(p:), achar(10))
        if (q == 0) then
            q = len(text) + 1
        else
            q = p + q - 1
        end if
        line = text(p:q - 1)
        p = q + 1
    end subroutine next_line

    !> The card `key` whose field F1 holds `name` (any such card when name
    !! is blank) and, when `name2` is given and not blank, whose field F2
    !! holds `name2`, and, when `name23` is given and not blank, whose field
    !! F2 or F3 holds `name23`, among `lines`: how many there are (and which, in
    !! `matches`), and for exactly one the line holding field number `field`
    !! counted across the card and its continuation cards (F8 is F1 of the
    !! first continuation card), with that field's columns. line = 0 when the
    !! card has no continuation card for the field.
    pure subroutine locate_field(lines, key, name, field, nfound, line, c1, c2, name2, matches, name23)
        type(deck_line_t), intent(in) :: lines(:)  !! card images
        character(len=*), intent(in) :: key        !! card name (columns 1-8)
        character(len=*), intent(in) :: name       !! name in field F1, or blank
        integer, intent(in) :: field               !! field number across the card, 1..3*nfields
        integer, intent(out) :: nfound             !! number of matching cards
        integer, intent(out) :: line               !! index in lines of the field's card image (0: none)
        integer, intent(out) :: c1                 !! the field's first column
        integer, intent(out) :: c2                 !! the field's last column
        character(len=*), intent(in), optional :: name2          !! text in field F2 too (absent or blank: any)
        integer, allocatable, intent(out), optional :: matches(:) !! the matching card images, in deck order
        character(len=*), intent(in), optional :: name23         !! text in field F2 or F3 (absent or blank: any)
        integer :: i, k
        logical :: second, either
        nfound = 0
        k = 0
        line = 0
        second = .false.
        if (present(name2)) second = len_trim(name2) > 0
        either = .false.
        if (present(name23)) either = len_trim(name23) > 0
        if (present(matches)) allocate (matches(0))
        call field_columns(1 + mod(field - 1, nfields), c1, c2)
        do i = 1, size(lines)
            if (upper(lines(i)%text(1:8)) /= upper(key)) cycle
            if (len_trim(name) > 0) then
                if (upper(adjustl(lines(i)%text(11:20))) /= upper(name)) cycle
            end if
            if (second) then
                if (upper(adjustl(lines(i)%text(21:30))) /= upper(name2)) cycle
            end if
            if (either) then
                if (upper(adjustl(lines(i)%text(21:30))) /= upper(name23) .and. &
                    upper(adjustl(lines(i)%text(31:40))) /= upper(name23)) cycle
            end if
            nfound = nfound + 1
            k = i
            if (present(matches)) matches = [matches, i]
        end do
        if (nfound /= 1) return
        line = k + (field - 1)/nfields
        if (line > size(lines)) then
            line = 0
        else if (line /= k .and. len_trim(lines(line)%text(1:10)) /= 0) then
            line = 0
        end if
    end subroutine locate_field

    !> A data file named on card image i (a TABLE's CSV file): looked for as
    !! INCLUDE files are (next to the file holding the card, the working
    !! directory, the include path) and read whole; only regular files, at
    !! most max_deck_bytes. stat /= 0 with a message otherwise.
    subroutine read_data_file(me, i, name, path, bytes, stat, errmsg)
        class(deck_reader_t), intent(in) :: me
        integer, intent(in) :: i                             !! card image naming the file
        character(len=*), intent(in) :: name                 !! the file name as written
        character(len=:), allocatable, intent(out) :: path   !! where it was found
        character(len=:), allocatable, intent(out) :: bytes  !! its contents
        integer, intent(out) :: stat                         !! stat_ok or stat_bad_input
        character(len=*), intent(out) :: errmsg              !! why it could not be read
        call resolve_include(me, name, me%lines(i)%source, path, errmsg)
        stat = stat_bad_input
        if (len(path) == 0) return
        call read_bytes(path, max_deck_bytes, bytes, stat, errmsg)
        if (stat /= 0) then
            errmsg = '"'//path//'": '//trim(errmsg)
            stat = stat_bad_input
        end if
    end subroutine read_data_file

    !> Append the directories of the environment variable HHNECK_PATH (colon
    !! separated, empty entries skipped) to the include path `search`: the
    !! place of the shipped decks for an installed hhneck, after -I DIR.
    subroutine add_environment_path(search)
        character(len=path_len), allocatable, intent(inout) :: search(:)  !! the include path, extended
        character(len=4096) :: env
        integer :: n, st, a, b
        if (.not. allocated(search)) allocate (search(0))
        call get_environment_variable('HHNECK_PATH', env, n, st)
        if (st /= 0 .or. n == 0) return
        a = 1
        do while (a <= n)
            b = index(env(a:n), ':')
            if (b == 0) then
                b = n + 1
            else
                b = a + b - 1
            end if
            if (b > a) search = [character(len=path_len) :: search, env(a:b - 1)]
            a = b + 1
        end do
    end subroutine add_environment_path

end module hn_deck_reader
