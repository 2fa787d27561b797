!> Reading back an HDF5 file (a result file, a dump): the shape of a
!! dataset, its real values, a text attribute, and a list attribute of
!! variable-length strings (hn_h5's attr_strings; an older file's single
!! space-separated text is read as its words). Each call opens and closes
!! the file, with HDF5's own printing of errors off; a missing file,
!! object or attribute gives stat /= 0, never a crash.
module hn_h5_read
    use, intrinsic :: iso_c_binding, only: c_loc, c_ptr, c_int, c_char, c_size_t, c_null_char
    use hdf5
    use hn_kinds, only: wp
    use hn_h5, only: h5_quiet, c_text, max_rank
    implicit none
    private

    public :: h5_read_real, h5_dims, h5_read_string_attr, h5_read_string_list_attr

    !> One text of a list being read.
    type :: text_t
        character(len=:), allocatable :: s
    end type text_t

    interface
        function c_h5free_memory(p) bind(C, name='H5free_memory') result(r)
            import :: c_ptr, c_int
            type(c_ptr), value :: p
            integer(c_int) :: r
        end function c_h5free_memory
    end interface

contains

    !> Shape of dataset `path` in file `fname` (Fortran order); stat /= 0 if absent.
    subroutine h5_dims(fname, path, dims, stat)
        character(len=*), intent(in) :: fname         !! HDF5 file name
        character(len=*), intent(in) :: path          !! dataset path in it
        integer, allocatable, intent(out) :: dims(:)  !! its shape
        integer, intent(out) :: stat                  !! 0 on success
        integer(hid_t) :: f, dset, space
        integer(hsize_t) :: d(max_rank), m(max_rank)
        integer :: r, err
        call h5_quiet()
        allocate (dims(0))
        call h5fopen_f(fname, H5F_ACC_RDONLY_F, f, stat)
        if (stat /= 0) then
            call h5eclear_f(err); return
        end if
        call h5dopen_f(f, path, dset, stat)
        if (stat == 0) then
            call h5dget_space_f(dset, space, stat)
            if (stat == 0) call h5sget_simple_extent_ndims_f(space, r, stat)
            if (stat == 0 .and. r >= 0 .and. r <= max_rank) then
                call h5sget_simple_extent_dims_f(space, d(1:r), m(1:r), err)
                if (err >= 0) then
                    dims = int(d(1:r))
                else
                    stat = -1
                end if
            else if (stat == 0) then
                stat = -1
            end if
            call h5sclose_f(space, err)
            call h5dclose_f(dset, err)
        end if
        call h5fclose_f(f, err)
        call h5eclear_f(err)
    end subroutine h5_dims

    !> Read a whole real dataset into buf (size must match); stat /= 0 on failure.
    subroutine h5_read_real(fname, path, buf, stat)
        character(len=*), intent(in) :: fname         !! HDF5 file name
        character(len=*), intent(in) :: path          !! dataset path in it
        real(wp), intent(out), target :: buf(*)       !! values, Fortran order
        integer, intent(out) :: stat                  !! 0 on success
        integer(hid_t) :: f, dset
        type(c_ptr) :: cp
        integer :: err
        call h5_quiet()
        call h5fopen_f(fname, H5F_ACC_RDONLY_F, f, stat)
        if (stat /= 0) then
            call h5eclear_f(err); return
        end if
        call h5dopen_f(f, path, dset, stat)
        if (stat == 0) then
            cp = c_loc(buf)
            call h5dread_f(dset, H5T_NATIVE_DOUBLE, cp, stat)
            call h5dclose_f(dset, err)
        end if
        call h5fclose_f(f, err)
        call h5eclear_f(err)
    end subroutine h5_read_real

    !> Open file fname read-only (HDF5's messages off) and attribute `name`
    !! of object `path` in it: f < 0 when the file cannot be opened (stat /= 0,
    !! the error stack cleared); else stat /= 0 when the attribute cannot be
    !! opened, and the caller closes f.
    subroutine open_attribute(fname, path, name, f, attr, stat)
        character(len=*), intent(in) :: fname, path, name
        integer(hid_t), intent(out) :: f, attr
        integer, intent(out) :: stat
        integer :: err
        attr = -1
        call h5_quiet()
        call h5fopen_f(fname, H5F_ACC_RDONLY_F, f, stat)
        if (stat /= 0) then
            f = -1
            call h5eclear_f(err); return
        end if
        call h5aopen_by_name_f(f, path, name, attr, stat)
    end subroutine open_attribute

    !> Read a text attribute of object `path`, fixed-length or variable-length.
    subroutine h5_read_string_attr(fname, path, name, value, stat)
        character(len=*), intent(in) :: fname               !! HDF5 file name
        character(len=*), intent(in) :: path                !! the object (group or dataset)
        character(len=*), intent(in) :: name                !! attribute name
        character(len=*), intent(out) :: value              !! its text
        integer, intent(out) :: stat                        !! 0 on success
        integer(hid_t) :: f, attr, ftype, mtype
        integer(size_t) :: tsize
        integer :: err, k
        logical :: is_var
        type(c_ptr), target :: ptr(1)
        type(c_ptr) :: cp
        character(len=len(value) + 1), target :: buf
        character(len=:), allocatable :: txt
        value = ''
        call open_attribute(fname, path, name, f, attr, stat)
        if (f < 0) return
        if (stat == 0) then
            call h5aget_type_f(attr, ftype, stat)
            if (stat == 0) call h5tis_variable_str_f(ftype, is_var, stat)
            if (stat == 0 .and. is_var) then
                call h5tcopy_f(ftype, mtype, stat)     ! same character set as stored
                cp = c_loc(ptr)
                call h5aread_f(attr, mtype, cp, stat)
                if (stat == 0) then
                    txt = c_text(ptr(1))
                    value = txt
                    err = c_h5free_memory(ptr(1))
                end if
                call h5tclose_f(mtype, err)
            else if (stat == 0) then
                call h5tget_size_f(ftype, tsize, stat)
                call h5tcopy_f(H5T_FORTRAN_S1, mtype, err)
                call h5tset_size_f(mtype, int(min(tsize, int(len(buf), size_t)), size_t), err)
                buf = ''
                cp = c_loc(buf)
                call h5aread_f(attr, mtype, cp, stat)
                ! only the attribute's own length is defined; it may end in a NUL
                if (tsize < len(buf)) buf(tsize + 1:) = ''
                k = index(buf, achar(0))
                if (k > 0) buf(k:) = ''
                value = buf
                call h5tclose_f(mtype, err)
            end if
            call h5tclose_f(ftype, err)
            call h5aclose_f(attr, err)
        end if
        call h5fclose_f(f, err)
        call h5eclear_f(err)
    end subroutine h5_read_string_attr

    !> Read a list attribute of object `path`: a one-dimensional array of
    !! strings (variable- or fixed-length, any character set; trailing
    !! blanks and NULs dropped), or one text whose blank-separated words are
    !! the items (how files before schema version 2 wrote lists). stat /= 0
    !! when the file, the object or the attribute is missing or the
    !! attribute is not text of rank 0 or 1.
    subroutine h5_read_string_list_attr(fname, path, name, items, stat)
        character(len=*), intent(in) :: fname                     !! HDF5 file name
        character(len=*), intent(in) :: path                      !! the object (group or dataset)
        character(len=*), intent(in) :: name                      !! attribute name
        character(len=:), allocatable, intent(out) :: items(:)    !! the list, in order
        integer, intent(out) :: stat                              !! 0 on success
        integer(hid_t) :: f, attr
        type(text_t), allocatable :: texts(:)
        integer :: err, k, lmax, rank
        allocate (character(len=1) :: items(0))
        call open_attribute(fname, path, name, f, attr, stat)
        if (f < 0) return
        if (stat == 0) then
            call read_attr_texts(attr, texts, rank, stat)
            call h5aclose_f(attr, err)
        end if
        call h5fclose_f(f, err)
        call h5eclear_f(err)
        if (stat /= 0) return
        if (rank == 0) texts = words(texts(1)%s)
        lmax = 1
        do k = 1, size(texts)
            lmax = max(lmax, len(texts(k)%s))
        end do
        deallocate (items)
        allocate (character(len=lmax) :: items(size(texts)))
        do k = 1, size(texts)
            items(k) = texts(k)%s
        end do
    end subroutine h5_read_string_list_attr

    !> The texts of a string attribute of rank 0 or 1 (stat /= 0 otherwise).
    subroutine read_attr_texts(attr, texts, rank, stat)
        integer(hid_t), intent(in) :: attr
        type(text_t), allocatable, intent(out) :: texts(:)
        integer, intent(out) :: rank, stat
        integer(hid_t) :: ftype, mtype, space
        integer(hsize_t) :: npts, dims(1), maxdims(1)
        integer(size_t) :: tsize
        integer :: err, k, j, n, cls, m
        logical :: is_var
        type(c_ptr), allocatable, target :: ptr(:)
        character(kind=c_char), allocatable, target :: cbuf(:)
        type(c_ptr) :: cp
        allocate (texts(0))
        rank = -1
        call h5aget_space_f(attr, space, stat)
        if (stat /= 0) return
        call h5sget_simple_extent_ndims_f(space, rank, stat)
        ! the extent, not H5Sget_simple_extent_npoints: its Fortran wrapper
        ! reports an empty dataspace as a failure
        npts = 1
        if (stat >= 0 .and. rank == 1) call h5sget_simple_extent_dims_f(space, dims, maxdims, stat)
        if (stat >= 0 .and. rank == 1) npts = dims(1)
        call h5sclose_f(space, err)
        if (stat < 0 .or. rank > 1) then
            stat = -1; return
        end if
        stat = 0
        n = int(npts)
        call h5aget_type_f(attr, ftype, stat)
        if (stat /= 0) return
        call h5tget_class_f(ftype, cls, stat)
        if (stat == 0 .and. cls /= H5T_STRING_F) stat = -1
        if (stat == 0) call h5tis_variable_str_f(ftype, is_var, stat)
        if (stat == 0) call h5tcopy_f(ftype, mtype, stat)     ! as stored: same character set and padding
        if (stat /= 0) then
            call h5tclose_f(ftype, err); return
        end if
        deallocate (texts)
        allocate (texts(n))
        if (is_var) then
            allocate (ptr(max(1, n)))
            cp = c_loc(ptr)
            if (n > 0) call h5aread_f(attr, mtype, cp, stat)
            do k = 1, n
                if (stat == 0) texts(k)%s = c_text(ptr(k))
                if (stat == 0) err = c_h5free_memory(ptr(k))
            end do
        else
            call h5tget_size_f(ftype, tsize, stat)
            m = int(tsize)
            allocate (cbuf(max(1, m*n)))
            cp = c_loc(cbuf)
            if (stat == 0 .and. n > 0) call h5aread_f(attr, mtype, cp, stat)
            do k = 1, n
                texts(k)%s = repeat(' ', m)
                do j = 1, m
                    texts(k)%s(j:j) = cbuf((k - 1)*m + j)
                end do
                j = index(texts(k)%s, achar(0))
                if (j > 0) texts(k)%s = texts(k)%s(1:j - 1)
                texts(k)%s = trim(texts(k)%s)
            end do
        end if
        if (stat == 0) then
            do k = 1, n
                if (.not. allocated(texts(k)%s)) texts(k)%s = ''
                texts(k)%s = trim(texts(k)%s)
            end do
        end if
        call h5tclose_f(mtype, err)
        call h5tclose_f(ftype, err)
    end subroutine read_attr_texts

    !> The blank-separated words of s.
    function words(s) result(w)
        character(len=*), intent(in) :: s
        type(text_t), allocatable :: w(:)
        integer :: k, n, start
        allocate (w(0))
        n = len(s)
        k = 1
        do while (k <= n)
            if (s(k:k) == ' ') then
                k = k + 1
                cycle
            end if
            start = k
            do while (k <= n)
                if (s(k:k) == ' ') exit
                k = k + 1
            end do
            w = [w, text_t(s(start:k - 1))]
        end do
    end function words

end module hn_h5_read
