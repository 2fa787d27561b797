!> Text helpers shared across the layers: strict parsing of a real number,
!! numbers as card fields and as text, upper case, and names taken from
!! paths.
module hn_strings
    use, intrinsic :: iso_c_binding, only: c_char, c_ptr, c_double, c_null_char, c_null_ptr
    use hn_kinds, only: wp
    implicit none
    private

    public :: int_field, path_stem, int_str, upper, parse_real, field_text, field_value

    interface
        function c_strtod(str, endptr) bind(C, name='strtod') result(v)
            import :: c_char, c_ptr, c_double
            character(kind=c_char), intent(in) :: str(*)
            type(c_ptr), value :: endptr
            real(c_double) :: v
        end function c_strtod
    end interface

contains

    !> n as a left-justified field of 10 columns.
    pure function int_field(n) result(f)
        integer, intent(in) :: n   !! the number
        character(len=10) :: f
        write (f, '(i0)') n
    end function int_field

    !> The name of a file without its folders and from its last '.inp' on:
    !! 'input/nbdl15g.inp' gives 'nbdl15g' (the whole name after the last
    !! '/' when it has no '.inp').
    pure function path_stem(path) result(stem)
        character(len=*), intent(in) :: path   !! the path
        character(len=:), allocatable :: stem
        integer :: a, b
        a = index(path, '/', back=.true.) + 1
        b = index(path, '.inp', back=.true.) - 1
        if (b < a) b = len_trim(path)
        stem = path(a:b)
    end function path_stem

    !> Strict real syntax: [sign] digits [. digits] | [sign] . digits, then an
    !! optional exponent (E or D) [sign] digits. Rejects NaN, Inf, commas,
    !! and numbers beyond the double range (overflow, or a non-zero number
    !! that would become zero) before converting, so that no conversion can
    !! raise a floating-point exception. `why` says what was wrong.
    subroutine parse_real(s, v, ok, why)
        character(len=*), intent(in) :: s     !! text of the number
        real(wp), intent(out) :: v            !! its value
        logical, intent(out) :: ok            !! the text is a representable real number
        character(len=*), intent(out), optional :: why  !! '' when ok; 'syntax', 'overflow' or 'underflow'
        character(len=len(s)) :: t
        integer :: k, n, nd, ios, first_nz, point, expo, e10, ke, j
        logical :: seen_dot
        character(len=40) :: mant
        real(wp) :: m
        t = upper(adjustl(s))
        n = len_trim(t)
        ok = .false.
        v = 0.0_wp
        if (present(why)) why = 'syntax'
        if (n == 0) return
        k = 1
        if (index('+-', t(k:k)) > 0) k = k + 1
        nd = 0; seen_dot = .false.
        first_nz = 0; point = 0
        do while (k <= n)
            if (index('0123456789', t(k:k)) > 0) then
                nd = nd + 1
                if (first_nz == 0 .and. t(k:k) /= '0') first_nz = nd
            else if (t(k:k) == '.' .and. .not. seen_dot) then
                seen_dot = .true.
                point = nd          ! digits before the point
            else
                exit
            end if
            k = k + 1
        end do
        if (nd == 0) return
        if (.not. seen_dot) point = nd
        expo = 0
        if (k <= n) then
            if (t(k:k) /= 'E' .and. t(k:k) /= 'D') return
            t(k:k) = 'E'
            ke = k + 1
            k = k + 1
            if (k <= n) then
                if (index('+-', t(k:k)) > 0) k = k + 1
            end if
            if (k > n) return
            do while (k <= n)
                if (index('0123456789', t(k:k)) == 0) return
                k = k + 1
            end do
            ! the exponent's digits, saturated (the field bounds their number, not their value)
            do j = ke, n
                if (index('+-', t(j:j)) > 0) cycle
                expo = min(10*expo + (iachar(t(j:j)) - 48), 99999)
            end do
            if (t(ke:ke) == '-') expo = -expo
        end if
        if (first_nz > 0) then
            ! decimal exponent of the leading significant digit
            e10 = expo + point - first_nz
            if (e10 > 308) then
                if (present(why)) why = 'overflow'
                return
            end if
            if (e10 < -324) then
                if (present(why)) why = 'underflow'
                return
            end if
            if (e10 == 308) then
                ! compare the significant digits with those of huge(1.0_wp) = 1.7976931348623157E308
                mant = significand(t(1:n), first_nz)
                read (mant, *, iostat=ios) m
                if (ios /= 0 .or. m >= 1.7976931348623157_wp) then
                    if (present(why)) why = 'overflow'
                    return
                end if
            end if
        end if
        ! syntax and range are checked: C's strtod converts (it is about 20
        ! times faster than a list-directed read, which matters for big decks)
        v = c_strtod(t(1:n)//c_null_char, c_null_ptr)
        if (first_nz > 0 .and. v == 0.0_wp) then
            if (present(why)) why = 'underflow'
            return
        end if
        ok = abs(v) <= huge(v)
        if (ok .and. present(why)) why = ''
    contains
        !> The significant digits as d.ddd (at most 30 of them).
        function significand(txt, nz) result(ms)
            character(len=*), intent(in) :: txt
            integer, intent(in) :: nz
            character(len=40) :: ms
            integer :: j, c, np
            ms = ''
            c = 0
            np = 0
            do j = 1, len(txt)
                if (txt(j:j) == 'E') exit
                if (index('0123456789', txt(j:j)) == 0) cycle
                c = c + 1
                if (c < nz) cycle
                np = np + 1
                if (np > 30) exit
                ms = trim(ms)//txt(j:j)
                if (np == 1) ms = trim(ms)//'.'
            end do
        end function significand
    end subroutine parse_real

    !> Upper-case copy of a string.
    pure function upper(s) result(u)
        character(len=*), intent(in) :: s   !! the string (ASCII)
        character(len=len(s)) :: u
        integer :: k, c
        u = s
        do k = 1, len(s)
            c = iachar(s(k:k))
            if (c >= 97 .and. c <= 122) u(k:k) = achar(c - 32)
        end do
    end function upper

    !> The most precise text of v that fits a 10-column field.
    pure function field_text(v) result(s)
        real(wp), intent(in) :: v   !! the value
        character(len=10) :: s
        character(len=24) :: buf
        integer :: d, ios
        do d = 9, 1, -1
            write (buf, '(es24.'//achar(48 + d)//'e0)', iostat=ios) v
            if (ios /= 0) cycle
            buf = adjustl(buf)
            if (len_trim(buf) <= 10) exit
        end do
        s = buf(1:10)
    end function field_text

    !> v as it reads back from its field text.
    pure real(wp) function field_value(v) result(x)
        real(wp), intent(in) :: v   !! the value
        character(len=10) :: s
        integer :: ios
        s = field_text(v)
        read (s, *, iostat=ios) x
        if (ios /= 0) x = v
    end function field_value

    !> An integer as text, left-justified in 16 columns.
    pure function int_str(i) result(s)
        integer, intent(in) :: i   !! the integer
        character(len=16) :: s
        write (s, '(i0)') i
    end function int_str

end module hn_strings
