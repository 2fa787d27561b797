!> A small HDF5 layer for results: fixed datasets, time series that grow by
!! one record per output time (chunked, unlimited in time), string and real
!! attributes, and reading back. The file is written under a temporary
!! name and renamed to its final name when closed complete, so a run that
!! dies leaves no file under the final name that could be mistaken for a
!! finished result.
!!
!! Time is the last Fortran dimension of a series, hence the first one seen
!! from h5py (C order): a series of records of shape (3, nb) reads in h5py
!! as an array of shape (nt, nb, 3).
module hn_h5
    use, intrinsic :: iso_c_binding, only: c_loc, c_ptr
    use hdf5
    use h5lt, only: h5ltset_attribute_string_f, h5ltset_attribute_double_f
    use hn_kinds, only: wp, msglen
    implicit none
    private

    public :: h5_file_t, h5_read_real, h5_dims, h5_read_string_attr

    !> An HDF5 result file being written.
    type :: h5_file_t
        integer(hid_t) :: id = -1
        character(len=:), allocatable :: final_name   !! name once complete
        character(len=:), allocatable :: temp_name    !! name while writing
        logical :: is_open = .false.
    contains
        procedure :: create => h5_create
        procedure :: close => h5_close
        procedure :: group => h5_group
        procedure :: write_real => h5_write_real
        procedure :: write_int => h5_write_int
        procedure :: write_strings => h5_write_strings
        procedure :: attr_string => h5_attr_string
        procedure :: attr_real => h5_attr_real
        procedure :: series => h5_series
        procedure :: append => h5_append
        procedure :: flush => h5_flush
    end type h5_file_t

contains

    !> Create `name` (written as name//'.part' until closed complete).
    subroutine h5_create(me, name, stat, errmsg)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: name
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        errmsg = ''
        call h5open_f(stat)
        if (stat /= 0) then
            errmsg = 'cannot initialise the HDF5 library'; return
        end if
        me%final_name = name
        me%temp_name = name//'.part'
        call h5fcreate_f(me%temp_name, H5F_ACC_TRUNC_F, me%id, stat)
        if (stat /= 0) then
            errmsg = 'cannot create HDF5 file '//me%temp_name; return
        end if
        me%is_open = .true.
    end subroutine h5_create

    !> Close; when `complete`, rename to the final name. When not complete
    !! the file stays under its temporary name, valid up to the last flush.
    subroutine h5_close(me, complete, stat, errmsg)
        class(h5_file_t), intent(inout) :: me
        logical, intent(in) :: complete
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        errmsg = ''
        stat = 0
        if (.not. me%is_open) return
        call h5fclose_f(me%id, stat)
        me%is_open = .false.
        if (stat /= 0) then
            errmsg = 'error closing HDF5 file '//me%temp_name; return
        end if
        if (complete) then
            call rename(me%temp_name, me%final_name, stat)
            if (stat /= 0) errmsg = 'cannot rename '//me%temp_name//' to '//me%final_name
        end if
    end subroutine h5_close

    !> Create group `path` (its parent must exist).
    subroutine h5_group(me, path)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path
        integer(hid_t) :: g
        integer :: err
        logical :: exists
        call h5lexists_f(me%id, path, exists, err)
        if (exists) return
        call h5gcreate_f(me%id, path, g, err)
        call h5gclose_f(g, err)
    end subroutine h5_group

    !> Write a fixed real dataset of shape dims from contiguous data.
    subroutine h5_write_real(me, path, buf, dims)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path
        real(wp), intent(in), target :: buf(*)
        integer, intent(in) :: dims(:)
        call write_any(me%id, path, H5T_NATIVE_DOUBLE, c_loc(buf), dims)
    end subroutine h5_write_real

    !> Write a fixed integer dataset.
    subroutine h5_write_int(me, path, buf, dims)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path
        integer, intent(in), target :: buf(*)
        integer, intent(in) :: dims(:)
        call write_any(me%id, path, H5T_NATIVE_INTEGER, c_loc(buf), dims)
    end subroutine h5_write_int

    !> Write a one-dimensional dataset of fixed-length strings (h5py reads
    !! them as bytes; trailing blanks are kept).
    subroutine h5_write_strings(me, path, strings)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path
        character(len=*), intent(in), target, contiguous :: strings(:)
        integer(hid_t) :: stype
        integer :: err
        call h5tcopy_f(H5T_FORTRAN_S1, stype, err)
        call h5tset_size_f(stype, int(max(len(strings), 1), size_t), err)
        call write_any(me%id, path, stype, c_loc(strings), [size(strings)])
        call h5tclose_f(stype, err)
    end subroutine h5_write_strings

    subroutine write_any(loc, path, dtype, ptr, dims)
        integer(hid_t), intent(in) :: loc, dtype
        character(len=*), intent(in) :: path
        type(c_ptr), intent(in) :: ptr
        integer, intent(in) :: dims(:)
        integer(hid_t) :: space, dset
        integer(hsize_t) :: hd(max(size(dims), 1))
        integer :: err
        if (size(dims) == 0) then
            call h5screate_f(H5S_SCALAR_F, space, err)
        else
            hd = int(dims, hsize_t)
            call h5screate_simple_f(size(dims), hd, space, err)
        end if
        call h5dcreate_f(loc, path, dtype, space, dset, err)
        call h5dwrite_f(dset, dtype, ptr, err)
        call h5dclose_f(dset, err)
        call h5sclose_f(space, err)
    end subroutine write_any

    !> String attribute on the object `path`.
    subroutine h5_attr_string(me, path, name, value)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path, name, value
        integer :: err
        call h5ltset_attribute_string_f(me%id, path, name, value, err)
    end subroutine h5_attr_string

    !> Real attribute (scalar or vector) on the object `path`.
    subroutine h5_attr_real(me, path, name, value)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path, name
        real(wp), intent(in) :: value(:)
        integer :: err
        call h5ltset_attribute_double_f(me%id, path, name, value, int(size(value), size_t), err)
    end subroutine h5_attr_real

    !> Create an empty time series whose records have shape dims.
    subroutine h5_series(me, path, dims)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path
        integer, intent(in) :: dims(:)
        integer(hsize_t) :: cur(size(dims) + 1), mx(size(dims) + 1), chunk(size(dims) + 1)
        integer(hid_t) :: space, dset, plist
        integer :: err, r, rec
        r = size(dims) + 1
        cur(1:r - 1) = int(dims, hsize_t); cur(r) = 0
        mx(1:r - 1) = int(dims, hsize_t); mx(r) = H5S_UNLIMITED_F
        rec = max(1, product(dims))
        chunk(1:r - 1) = int(dims, hsize_t)
        chunk(r) = int(max(1, min(4096, 32768/rec)), hsize_t)
        call h5screate_simple_f(r, cur, space, err, mx)
        call h5pcreate_f(H5P_DATASET_CREATE_F, plist, err)
        call h5pset_chunk_f(plist, r, chunk, err)
        call h5dcreate_f(me%id, path, H5T_NATIVE_DOUBLE, space, dset, err, plist)
        call h5pclose_f(plist, err)
        call h5dclose_f(dset, err)
        call h5sclose_f(space, err)
    end subroutine h5_series

    !> Append `nrec` records (default 1) to the time series `path`.
    subroutine h5_append(me, path, buf, nrec)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path
        real(wp), intent(in), target :: buf(*)
        integer, intent(in), optional :: nrec
        integer(hid_t) :: dset, fspace, mspace
        integer(hsize_t) :: dims(8), maxd(8), start(8), cnt(8), nr
        integer :: err, r
        nr = 1
        if (present(nrec)) nr = int(nrec, hsize_t)
        if (nr < 1) return
        call h5dopen_f(me%id, path, dset, err)
        call h5dget_space_f(dset, fspace, err)
        call h5sget_simple_extent_ndims_f(fspace, r, err)
        call h5sget_simple_extent_dims_f(fspace, dims(1:r), maxd(1:r), err)
        call h5sclose_f(fspace, err)
        dims(r) = dims(r) + nr
        call h5dset_extent_f(dset, dims(1:r), err)
        call h5dget_space_f(dset, fspace, err)
        start(1:r) = 0; start(r) = dims(r) - nr
        cnt(1:r) = dims(1:r); cnt(r) = nr
        call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, start(1:r), cnt(1:r), err)
        call h5screate_simple_f(r, cnt(1:r), mspace, err)
        call h5dwrite_f(dset, H5T_NATIVE_DOUBLE, c_loc(buf), err, mspace, fspace)
        call h5sclose_f(mspace, err)
        call h5sclose_f(fspace, err)
        call h5dclose_f(dset, err)
    end subroutine h5_append

    !> Flush everything written so far to disk.
    subroutine h5_flush(me)
        class(h5_file_t), intent(inout) :: me
        integer :: err
        if (me%is_open) call h5fflush_f(me%id, H5F_SCOPE_GLOBAL_F, err)
    end subroutine h5_flush

    !> Shape of dataset `path` in file `fname` (Fortran order); stat /= 0 if absent.
    subroutine h5_dims(fname, path, dims, stat)
        character(len=*), intent(in) :: fname, path
        integer, allocatable, intent(out) :: dims(:)
        integer, intent(out) :: stat
        integer(hid_t) :: f, dset, space
        integer(hsize_t) :: d(8), m(8)
        integer :: r, err
        call h5open_f(err)
        call h5fopen_f(fname, H5F_ACC_RDONLY_F, f, stat)
        if (stat /= 0) return
        call h5dopen_f(f, path, dset, stat)
        if (stat == 0) then
            call h5dget_space_f(dset, space, err)
            call h5sget_simple_extent_ndims_f(space, r, err)
            call h5sget_simple_extent_dims_f(space, d(1:r), m(1:r), err)
            dims = int(d(1:r))
            call h5sclose_f(space, err)
            call h5dclose_f(dset, err)
        end if
        call h5fclose_f(f, err)
    end subroutine h5_dims

    !> Read a whole real dataset into buf (size must match); stat /= 0 on failure.
    subroutine h5_read_real(fname, path, buf, stat)
        character(len=*), intent(in) :: fname, path
        real(wp), intent(out), target :: buf(*)
        integer, intent(out) :: stat
        integer(hid_t) :: f, dset
        integer :: err
        type(c_ptr) :: ptr
        call h5open_f(err)
        call h5fopen_f(fname, H5F_ACC_RDONLY_F, f, stat)
        if (stat /= 0) return
        call h5dopen_f(f, path, dset, stat)
        if (stat == 0) then
            ptr = c_loc(buf)
            call h5dread_f(dset, H5T_NATIVE_DOUBLE, ptr, stat)
            call h5dclose_f(dset, err)
        end if
        call h5fclose_f(f, err)
    end subroutine h5_read_real

    !> Read a string attribute of object `path`.
    subroutine h5_read_string_attr(fname, path, name, value, stat)
        use h5lt, only: h5ltget_attribute_string_f, h5ltget_attribute_info_f
        character(len=*), intent(in) :: fname, path, name
        character(len=*), intent(out) :: value
        integer, intent(out) :: stat
        integer(hid_t) :: f
        integer(hsize_t) :: dims(1)
        integer(size_t) :: tsize
        integer :: err, tclass
        value = ''
        call h5open_f(err)
        call h5fopen_f(fname, H5F_ACC_RDONLY_F, f, stat)
        if (stat /= 0) return
        call h5ltget_attribute_info_f(f, path, name, dims, tclass, tsize, stat)
        if (stat == 0) call h5ltget_attribute_string_f(f, path, name, value, stat)
        call h5fclose_f(f, err)
        ! only the attribute's own length is defined; it may end in a NUL
        if (tsize < len(value)) value(tsize + 1:) = ''
        err = index(value, achar(0))
        if (err > 0) value(err:) = ''
    end subroutine h5_read_string_attr

end module hn_h5
