!> Text helpers shared across the layers: numbers as card fields and names
!! taken from paths.
module hn_strings
    implicit none
    private

    public :: int_field, path_stem

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

end module hn_strings
