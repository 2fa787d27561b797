!> A small HDF5 layer for writing results: fixed datasets, time series
!! that grow by blocks of records (chunked, unlimited in time, kept open
!! while the file is written), text and real attributes (reading back:
!! hn_h5_read).
!!
!! Every HDF5 call is checked. HDF5's own printing of errors is turned off;
!! the first failure is kept in the file object as one message that
!! summarises HDF5's error stack ("H5Dwrite: can't write data: No space
!! left on device"), and every later call on that file does nothing, so a
!! full disk cannot cascade into more errors or a crash.
!!
!! Files tell the truth: the file is written under NAME.part and renamed to
!! NAME only when closed after no error; a run that has an error removes its
!! NAME.part and says so. An exclusive lock file NAME.lock (holding the
!! process id and host) keeps two runs from writing one result name at the
!! same time, with or without HDF5's own file locking; a lock left by a
!! process that no longer exists on this host is taken over. An older NAME
!! is removed when a new run starts writing it, so that it cannot be taken
!! for the new run's result.
!!
!! Text attributes are variable-length UTF-8 strings (h5py reads them as
!! str); lists (names, labels, units) are one-dimensional attributes of
!! such strings (attr_strings; h5py reads a numpy array of str). Integer attributes are
!! integers (attr_int). Time is the last Fortran dimension of a series, hence the first one
!! seen from h5py (C order): a series of records of shape (3, nb) reads in
!! h5py as an array of shape (nt, nb, 3).
module hn_h5
    use, intrinsic :: iso_c_binding, only: c_loc, c_ptr, c_int, c_char, c_null_char, c_funptr, c_funloc, &
                                           c_size_t, c_associated, c_f_pointer, c_long
    use hdf5
    use hn_kinds, only: wp, msglen
    use hn_status, only: stat_ok, stat_io
    use hn_posix, only: file_kind, kind_missing, kind_regular, kind_directory, kind_name, make_directories, &
                        remove_file, rename_file, parent_directory, process_id, process_alive, host_name
    implicit none
    private

    public :: h5_file_t, h5_quiet, c_text

    integer, parameter, public :: max_rank = 8   !! highest rank of a dataset written or read

    !> An open time series.
    type :: series_t
        character(len=:), allocatable :: path
        integer(hid_t) :: dset = -1
        integer :: rank = 0
        integer(hsize_t) :: dims(max_rank) = 0   !! current extent (time last)
    end type series_t

    !> An HDF5 result file being written.
    type :: h5_file_t
        integer(hid_t) :: id = -1
        character(len=:), allocatable :: final_name   !! name once complete
        character(len=:), allocatable :: temp_name    !! name while writing
        character(len=:), allocatable :: lock_name    !! exclusive lock while writing
        logical :: is_open = .false.
        logical :: locked = .false.
        integer :: stat = stat_ok                      !! first failure (sticky)
        character(len=msglen) :: errmsg = ''           !! its message
        character(len=msglen) :: note = ''             !! what create did to files already there
        type(series_t), allocatable :: ser(:)
        integer :: nser = 0, last = 0
    contains
        procedure :: create => h5_create
        procedure :: close => h5_close
        procedure :: failed => h5_failed
        procedure :: group => h5_group
        procedure :: write_real => h5_write_real
        procedure :: write_int => h5_write_int
        procedure :: write_strings => h5_write_strings
        procedure :: attr_string => h5_attr_string
        procedure :: attr_real => h5_attr_real
        procedure :: attr_strings => h5_attr_strings
        procedure :: attr_int => h5_attr_int
        procedure :: attr_real_scalar => h5_attr_real_scalar
        procedure :: write_text => h5_write_text
        procedure :: series => h5_series
        procedure :: append => h5_append
        procedure :: flush => h5_flush
    end type h5_file_t

    ! the parts of HDF5's error stack that the Fortran API does not offer
    type, bind(C) :: h5e_error2_t
        integer(hid_t) :: cls_id, maj_num, min_num
        integer(c_int) :: line
        type(c_ptr) :: func_name, file_name, desc
    end type h5e_error2_t

    !> What the error-stack walk collects.
    type :: stack_text_t
        character(len=400) :: inner = '', outer = '', outer_func = ''
        integer :: n = 0
    end type stack_text_t

    interface
        function c_h5ewalk2(estack, direction, func, client) bind(C, name='H5Ewalk2') result(r)
            import :: hid_t, c_int, c_funptr, c_ptr
            integer(hid_t), value :: estack
            integer(c_int), value :: direction
            type(c_funptr), value :: func
            type(c_ptr), value :: client
            integer(c_int) :: r
        end function c_h5ewalk2
        function c_strlen(p) bind(C, name='strlen') result(n)
            import :: c_ptr, c_size_t
            type(c_ptr), value :: p
            integer(c_size_t) :: n
        end function c_strlen
    end interface

contains

    !> Open the HDF5 library with its automatic error printing off (every
    !! call is checked here instead). Safe to call more than once.
    subroutine h5_quiet()
        integer :: err
        call h5open_f(err)
        call h5eset_auto_f(0, err)
    end subroutine h5_quiet

    logical function h5_failed(me)
        class(h5_file_t), intent(in) :: me
        h5_failed = me%stat /= stat_ok
    end function h5_failed

    !> One line from HDF5's error stack: the failing API call, what it
    !! could not do and, when the operating system said why, its reason.
    function h5_error_summary() result(s)
        character(len=:), allocatable :: s
        type(stack_text_t), target :: acc
        integer(c_int) :: r
        integer :: k1, k2, err
        r = c_h5ewalk2(0_hid_t, 0_c_int, c_funloc(walk_one), c_loc(acc))
        call h5eclear_f(err)
        if (acc%n == 0) then
            s = 'HDF5 reported an error without details'
            return
        end if
        s = trim(acc%outer_func)//': '//trim(acc%outer)
        k1 = index(acc%inner, "error message = '")
        if (k1 > 0) then
            k1 = k1 + len("error message = '")
            k2 = index(acc%inner(k1:), "'")
            if (k2 > 1) then
                s = s//': '//acc%inner(k1:k1 + k2 - 2)
                return
            end if
        end if
        if (acc%n > 1) then
            k1 = index(acc%inner, ':')
            if (k1 > 0) then
                s = s//' ('//trim(acc%inner(1:k1 - 1))//')'
            else
                s = s//' ('//trim(acc%inner(1:min(120, len_trim(acc%inner))))//')'
            end if
        end if
    end function h5_error_summary

    !> Callback of H5Ewalk2 (upward: the innermost entry first, the API call last).
    function walk_one(n, e, client) bind(C) result(r)
        integer(c_int), value :: n
        type(h5e_error2_t), intent(in) :: e
        type(c_ptr), value :: client
        integer(c_int) :: r
        type(stack_text_t), pointer :: acc
        call c_f_pointer(client, acc)
        if (acc%n == 0) acc%inner = c_text(e%desc)
        acc%outer = c_text(e%desc)
        acc%outer_func = c_text(e%func_name)
        acc%n = acc%n + 1
        r = 0
        if (n < 0) r = 0
    end function walk_one

    !> A C string as Fortran text ('' for a null pointer).
    function c_text(p) result(s)
        type(c_ptr), intent(in) :: p   !! the string (NUL-terminated)
        character(len=:), allocatable :: s
        character(kind=c_char), pointer :: c(:)
        integer :: n, k
        s = ''
        if (.not. c_associated(p)) return
        n = int(c_strlen(p))
        call c_f_pointer(p, c, [n])
        s = repeat(' ', n)
        do k = 1, n
            s(k:k) = c(k)
        end do
    end function c_text

    !> Record the first failure (HDF5 returns a negative code) with HDF5's reason.
    subroutine check(me, err, what)
        class(h5_file_t), intent(inout) :: me
        integer, intent(in) :: err
        character(len=*), intent(in) :: what
        integer :: e2
        if (err >= 0) return
        if (me%stat /= stat_ok) then
            call h5eclear_f(e2)
            return
        end if
        me%stat = stat_io
        me%errmsg = 'writing '//me%final_name//' failed ('//what//'): '//h5_error_summary()
    end subroutine check

    !> Record a failure that is not an HDF5 call's.
    subroutine fail(me, text)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: text
        if (me%stat /= stat_ok) return
        me%stat = stat_io
        me%errmsg = text
    end subroutine fail

    !> Create `name`, written as name//'.part' until closed. Creates a
    !! missing directory, takes the lock name//'.lock', removes an older
    !! `name`; what it did is in me%note. stat /= 0 with a one-line message
    !! when the file cannot be created (nothing is left behind then).
    subroutine h5_create(me, name, stat, errmsg)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: name          !! final file name
        integer, intent(out) :: stat                  !! stat_ok or stat_io
        character(len=msglen), intent(out) :: errmsg  !! the reason on failure
        character(len=:), allocatable :: dir
        integer :: st, kind
        call h5_quiet()
        if (me%is_open) call h5_close(me, .false., stat, errmsg)
        me%stat = stat_ok
        me%errmsg = ''
        me%nser = 0
        me%last = 0
        me%final_name = name
        me%temp_name = name//'.part'
        me%lock_name = name//'.lock'
        me%note = ''
        dir = parent_directory(name)
        if (len(dir) > 0) then
            kind = file_kind(dir)
            if (kind == kind_missing) then
                call make_directories(dir, st)
                if (st /= 0) then
                    call fail(me, 'cannot write '//name//': directory '//dir//' does not exist and cannot be created')
                else
                    call add_note(me, 'created directory '//dir)
                end if
            else if (kind /= kind_directory) then
                call fail(me, 'cannot write '//name//': '//dir//' is '//kind_name(kind)//', not a directory')
            end if
        end if
        kind = file_kind(name)
        if (kind /= kind_missing .and. kind /= kind_regular) &
            call fail(me, 'cannot write '//name//': it is '//kind_name(kind)//'; expected a file name for the results')
        if (me%stat == stat_ok) call take_lock(me)
        if (me%stat == stat_ok .and. kind == kind_regular) then
            call remove_file(name, st)
            if (st /= 0) then
                call fail(me, 'cannot replace the older result file '//name//' (permission denied?)')
            else
                call add_note(me, 'removed the older result file '//name//' (this run writes it anew)')
            end if
        end if
        kind = file_kind(me%temp_name)
        if (me%stat == stat_ok .and. kind /= kind_missing .and. kind /= kind_regular) &
            call fail(me, 'cannot write '//me%temp_name//': it is '//kind_name(kind))
        if (me%stat == stat_ok .and. kind == kind_regular) &
            call add_note(me, 'replaced '//me%temp_name//' left by an earlier run')
        if (me%stat == stat_ok) then
            call h5fcreate_f(me%temp_name, H5F_ACC_TRUNC_F, me%id, st)
            if (st < 0) then
                me%stat = stat_io
                me%errmsg = 'cannot create '//me%temp_name//': '//h5_error_summary()
            else
                me%is_open = .true.
            end if
        end if
        if (me%stat /= stat_ok) call release_lock(me)
        stat = me%stat
        errmsg = me%errmsg
    end subroutine h5_create

    subroutine add_note(me, text)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: text
        if (len_trim(me%note) > 0) then
            me%note = trim(me%note)//'; '//text
        else
            me%note = text
        end if
    end subroutine add_note

    !> Take NAME.lock (created exclusively, holding "pid host"); a lock of a
    !! process that no longer exists on this host is taken over.
    subroutine take_lock(me)
        class(h5_file_t), intent(inout) :: me
        integer :: u, ios, attempt, pid
        character(len=msglen) :: iomsg
        character(len=256) :: host
        do attempt = 1, 2
            open (newunit=u, file=me%lock_name, status='new', action='write', iostat=ios, iomsg=iomsg)
            if (ios == 0) then
                write (u, '(i0,1x,a)', iostat=ios) process_id(), host_name()
                close (u)
                me%locked = .true.
                return
            end if
            if (file_kind(me%lock_name) == kind_missing) then
                call fail(me, 'cannot write '//me%final_name//': cannot create files in its directory ('// &
                          trim(iomsg)//')')
                return
            end if
            ! held: by a live run, or left by one that died
            pid = 0
            host = ''
            open (newunit=u, file=me%lock_name, status='old', action='read', iostat=ios)
            if (ios == 0) then
                read (u, *, iostat=ios) pid, host
                close (u)
            end if
            if (attempt == 1 .and. pid > 0 .and. trim(host) == host_name() .and. .not. process_alive(pid)) then
                call remove_file(me%lock_name, ios)
                call add_note(me, 'removed the stale lock '//me%lock_name//' of process '//trim(int_text(pid))// &
                              ', which no longer runs')
                cycle
            end if
            call fail(me, 'cannot write '//me%final_name//': another run is writing it (process '// &
                      trim(int_text(pid))//' on '//trim(host)//' holds '//me%lock_name// &
                      '); wait for it, or choose another name; remove the lock only if no run writes the file')
            return
        end do
    end subroutine take_lock

    subroutine release_lock(me)
        class(h5_file_t), intent(inout) :: me
        integer :: st
        if (.not. me%locked) return
        call remove_file(me%lock_name, st)
        me%locked = .false.
    end subroutine release_lock

    pure function int_text(i) result(s)
        integer, intent(in) :: i
        character(len=16) :: s
        write (s, '(i0)') i
    end function int_text

    !> Close. After no error, and when `complete`, rename to the final name
    !! (atomically, replacing nothing since create removed an older file).
    !! After an error the temporary file is removed: stat /= 0 and errmsg
    !! says so. The lock is released in every case.
    subroutine h5_close(me, complete, stat, errmsg)
        class(h5_file_t), intent(inout) :: me
        logical, intent(in) :: complete               !! give the file its final name
        integer, intent(out) :: stat                  !! stat_ok or stat_io
        character(len=msglen), intent(out) :: errmsg  !! the reason on failure
        integer :: k, err, st
        if (me%is_open) then
            do k = 1, me%nser
                if (me%ser(k)%dset >= 0) call h5dclose_f(me%ser(k)%dset, err)
                if (me%ser(k)%dset >= 0) call check(me, err, 'closing '//me%ser(k)%path)
                me%ser(k)%dset = -1
            end do
            me%nser = 0
            call h5fclose_f(me%id, err)
            call check(me, err, 'closing the file')
            me%is_open = .false.
            if (me%stat /= stat_ok) then
                call remove_file(me%temp_name, st)
                if (st == 0) then
                    me%errmsg = trim(me%errmsg)//'; the partial file '//me%temp_name//' was removed'
                else
                    me%errmsg = trim(me%errmsg)//'; the partial file '//me%temp_name//' is not valid'
                end if
            else if (complete) then
                call rename_file(me%temp_name, me%final_name, st)
                if (st /= 0 .or. file_kind(me%final_name) /= kind_regular) &
                    call fail(me, 'cannot rename '//me%temp_name//' to '//me%final_name)
            end if
        end if
        call release_lock(me)
        stat = me%stat
        errmsg = me%errmsg
    end subroutine h5_close

    !> Create group `path` (its parent must exist).
    subroutine h5_group(me, path)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path   !! e.g. '/model'
        integer(hid_t) :: g
        integer :: err
        logical :: exists
        if (me%stat /= stat_ok) return
        call h5lexists_f(me%id, path, exists, err)
        call check(me, err, 'looking for '//path)
        if (exists .or. me%stat /= stat_ok) return
        call h5gcreate_f(me%id, path, g, err)
        call check(me, err, 'creating group '//path)
        if (err >= 0) call h5gclose_f(g, err)
    end subroutine h5_group

    !> Write a fixed real dataset of shape dims from contiguous data.
    subroutine h5_write_real(me, path, buf, dims)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path   !! dataset
        real(wp), intent(in), target :: buf(*) !! values, Fortran order
        integer, intent(in) :: dims(:)         !! shape ([] for a scalar)
        call write_any(me, path, H5T_NATIVE_DOUBLE, c_loc(buf), dims)
    end subroutine h5_write_real

    !> Write a fixed integer dataset.
    subroutine h5_write_int(me, path, buf, dims)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path   !! dataset
        integer, intent(in), target :: buf(*)  !! values, Fortran order
        integer, intent(in) :: dims(:)         !! shape
        call write_any(me, path, H5T_NATIVE_INTEGER, c_loc(buf), dims)
    end subroutine h5_write_int

    !> Write a one-dimensional dataset of fixed-length strings (h5py reads
    !! them as bytes; trailing blanks are kept).
    subroutine h5_write_strings(me, path, strings)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path                            !! dataset
        character(len=*), intent(in), target, contiguous :: strings(:)  !! one string per element
        integer(hid_t) :: stype
        integer :: err
        if (me%stat /= stat_ok) return
        call h5tcopy_f(H5T_FORTRAN_S1, stype, err)
        call check(me, err, 'string type')
        if (me%stat /= stat_ok) return
        call h5tset_size_f(stype, int(max(len(strings), 1), size_t), err)
        call check(me, err, 'string type')
        call write_any(me, path, stype, c_loc(strings), [size(strings)])
        call h5tclose_f(stype, err)
    end subroutine h5_write_strings

    !> Write a one-dimensional dataset of variable-length UTF-8 strings, each
    !! without its trailing blanks (h5py: `ds.asstr()[:]` gives str, `ds[:]`
    !! bytes).
    subroutine h5_write_text(me, path, strings)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path            !! dataset
        character(len=*), intent(in) :: strings(:)      !! one string per element
        character(kind=c_char), allocatable, target :: cbuf(:)
        type(c_ptr), allocatable, target :: ptr(:)
        integer(hid_t) :: stype
        integer :: err
        if (me%stat /= stat_ok) return
        call vlen_buffers(strings, cbuf, ptr)
        call vlen_utf8_type(me, stype)
        if (me%stat /= stat_ok) return
        call write_any(me, path, stype, c_loc(ptr), [size(strings)])
        call h5tclose_f(stype, err)
    end subroutine h5_write_text

    !> A variable-length UTF-8 string type (to be closed by the caller).
    subroutine vlen_utf8_type(me, stype)
        class(h5_file_t), intent(inout) :: me
        integer(hid_t), intent(out) :: stype
        integer :: err
        call h5tcopy_f(H5T_STRING, stype, err)
        call check(me, err, 'string type')
        if (me%stat /= stat_ok) return
        call h5tset_cset_f(stype, H5T_CSET_UTF8_F, err)
        call check(me, err, 'string type')
    end subroutine vlen_utf8_type

    !> The strings without trailing blanks, NUL-terminated one after the
    !! other in cbuf, and a pointer to each (what HDF5 writes as
    !! variable-length strings). ptr has at least one element.
    subroutine vlen_buffers(strings, cbuf, ptr)
        character(len=*), intent(in) :: strings(:)
        character(kind=c_char), allocatable, target, intent(out) :: cbuf(:)
        type(c_ptr), allocatable, intent(out) :: ptr(:)
        integer :: k, j, pos, n
        allocate (cbuf(sum(len_trim(strings)) + size(strings) + 1), ptr(max(1, size(strings))))
        pos = 1
        do k = 1, size(strings)
            n = len_trim(strings(k))
            do j = 1, n
                cbuf(pos + j - 1) = strings(k)(j:j)
            end do
            cbuf(pos + n) = c_null_char
            ptr(k) = c_loc(cbuf(pos))
            pos = pos + n + 1
        end do
        cbuf(pos) = c_null_char
        if (size(strings) == 0) ptr(1) = c_loc(cbuf(pos))
    end subroutine vlen_buffers

    subroutine write_any(me, path, dtype, ptr, dims)
        class(h5_file_t), intent(inout) :: me
        integer(hid_t), intent(in) :: dtype
        character(len=*), intent(in) :: path
        type(c_ptr), intent(in) :: ptr
        integer, intent(in) :: dims(:)
        integer(hid_t) :: space, dset
        integer(hsize_t) :: hd(max(size(dims), 1))
        integer :: err
        call new_space(me, dims, space, path)
        if (me%stat /= stat_ok) return
        call h5dcreate_f(me%id, path, dtype, space, dset, err)
        call check(me, err, 'creating '//path)
        if (err >= 0) then
            if (product(dims) > 0) then
                call h5dwrite_f(dset, dtype, ptr, err)
                call check(me, err, 'writing '//path)
            end if
            call h5dclose_f(dset, err)
            call check(me, err, 'closing '//path)
        end if
        call h5sclose_f(space, err)
    end subroutine write_any

    !> Text attribute on the object `path`, as a variable-length UTF-8
    !! string (h5py reads it as str); an attribute of that name is replaced.
    subroutine h5_attr_string(me, path, name, value)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path    !! the object (group or dataset)
        character(len=*), intent(in) :: name    !! attribute name
        character(len=*), intent(in) :: value   !! the text
        character(len=len(value) + 1, kind=c_char), target :: buf
        type(c_ptr), target :: ptr(1)
        integer(hid_t) :: stype, space, attr
        integer :: err
        if (me%stat /= stat_ok) return
        buf = value//c_null_char
        ptr(1) = c_loc(buf)
        call h5tcopy_f(H5T_STRING, stype, err)
        call check(me, err, 'string type')
        if (me%stat /= stat_ok) return
        call h5tset_cset_f(stype, H5T_CSET_UTF8_F, err)
        call check(me, err, 'string type')
        call new_attribute(me, path, name, stype, [integer ::], attr, space)
        if (me%stat == stat_ok) then
            call h5awrite_f(attr, stype, c_loc(ptr), err)
            call check(me, err, 'writing attribute '//name//' of '//path)
            call h5aclose_f(attr, err)
            call h5sclose_f(space, err)
        end if
        call h5tclose_f(stype, err)
    end subroutine h5_attr_string

    !> Real attribute (a vector, one element for a single value) on the object `path`.
    subroutine h5_attr_real(me, path, name, value)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path         !! the object (group or dataset)
        character(len=*), intent(in) :: name         !! attribute name
        real(wp), intent(in), target :: value(:)     !! value(s)
        integer(hid_t) :: space, attr
        integer :: err
        real(wp), target :: v(size(value))
        if (me%stat /= stat_ok) return
        v = value
        call new_attribute(me, path, name, H5T_NATIVE_DOUBLE, [size(value)], attr, space)
        if (me%stat /= stat_ok) return
        call h5awrite_f(attr, H5T_NATIVE_DOUBLE, c_loc(v), err)
        call check(me, err, 'writing attribute '//name//' of '//path)
        call h5aclose_f(attr, err)
        call h5sclose_f(space, err)
    end subroutine h5_attr_real

    !> List attribute on the object `path`: a one-dimensional array of
    !! variable-length UTF-8 strings, each without its trailing blanks
    !! (h5py reads a numpy array of str); an attribute of that name is
    !! replaced.
    subroutine h5_attr_strings(me, path, name, values)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path        !! the object (group or dataset)
        character(len=*), intent(in) :: name        !! attribute name
        character(len=*), intent(in) :: values(:)   !! the list, in order
        character(kind=c_char), allocatable, target :: cbuf(:)
        type(c_ptr), allocatable, target :: ptr(:)
        integer(hid_t) :: stype, space, attr
        integer :: err
        if (me%stat /= stat_ok) return
        call vlen_buffers(values, cbuf, ptr)
        call vlen_utf8_type(me, stype)
        if (me%stat /= stat_ok) return
        call new_attribute(me, path, name, stype, [size(values)], attr, space)
        if (me%stat == stat_ok) then
            if (size(values) > 0) then
                call h5awrite_f(attr, stype, c_loc(ptr), err)
                call check(me, err, 'writing attribute '//name//' of '//path)
            end if
            call h5aclose_f(attr, err)
            call h5sclose_f(space, err)
        end if
        call h5tclose_f(stype, err)
    end subroutine h5_attr_strings

    !> Scalar integer attribute on the object `path` (h5py reads a numpy
    !! integer); an attribute of that name is replaced.
    subroutine h5_attr_int(me, path, name, value)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path         !! the object (group or dataset)
        character(len=*), intent(in) :: name         !! attribute name
        integer, intent(in) :: value                 !! the value
        integer, target :: v
        v = value
        call scalar_attribute(me, path, name, H5T_NATIVE_INTEGER, c_loc(v))
    end subroutine h5_attr_int

    !> Scalar real attribute on the object `path` (h5py reads a float, not
    !! an array of one as from attr_real); an attribute of that name is
    !! replaced.
    subroutine h5_attr_real_scalar(me, path, name, value)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path         !! the object (group or dataset)
        character(len=*), intent(in) :: name         !! attribute name
        real(wp), intent(in) :: value                !! the value
        real(wp), target :: v
        v = value
        call scalar_attribute(me, path, name, H5T_NATIVE_DOUBLE, c_loc(v))
    end subroutine h5_attr_real_scalar

    !> A scalar attribute of type dtype from the value at buf.
    subroutine scalar_attribute(me, path, name, dtype, buf)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path, name
        integer(hid_t), intent(in) :: dtype
        type(c_ptr), intent(in) :: buf
        integer(hid_t) :: space, attr
        integer :: err
        if (me%stat /= stat_ok) return
        call new_attribute(me, path, name, dtype, [integer ::], attr, space)
        if (me%stat /= stat_ok) return
        call h5awrite_f(attr, dtype, buf, err)
        call check(me, err, 'writing attribute '//name//' of '//path)
        call h5aclose_f(attr, err)
        call h5sclose_f(space, err)
    end subroutine scalar_attribute

    !> A dataspace of shape dims (scalar when dims is empty).
    subroutine new_space(me, dims, space, what)
        class(h5_file_t), intent(inout) :: me
        integer, intent(in) :: dims(:)
        integer(hid_t), intent(out) :: space
        character(len=*), intent(in) :: what
        integer(hsize_t) :: hd(max(size(dims), 1))
        integer :: err
        if (size(dims) == 0) then
            call h5screate_f(H5S_SCALAR_F, space, err)
        else
            hd = int(dims, hsize_t)
            call h5screate_simple_f(size(dims), hd, space, err)
        end if
        call check(me, err, 'dataspace of '//what)
    end subroutine new_space

    !> A new attribute (an old one of that name deleted) and its dataspace.
    subroutine new_attribute(me, path, name, dtype, dims, attr, space)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path, name
        integer(hid_t), intent(in) :: dtype
        integer, intent(in) :: dims(:)
        integer(hid_t), intent(out) :: attr, space
        integer :: err
        logical :: exists
        attr = -1; space = -1
        call h5aexists_by_name_f(me%id, path, name, exists, err)
        call check(me, err, 'looking for attribute '//name//' of '//path)
        if (me%stat /= stat_ok) return
        if (exists) then
            call h5adelete_by_name_f(me%id, path, name, err)
            call check(me, err, 'replacing attribute '//name//' of '//path)
        end if
        call new_space(me, dims, space, 'attribute '//name)
        if (me%stat /= stat_ok) return
        call h5acreate_by_name_f(me%id, path, name, dtype, space, attr, err)
        call check(me, err, 'creating attribute '//name//' of '//path)
        if (me%stat /= stat_ok) call h5sclose_f(space, err)
    end subroutine new_attribute

    !> Create an empty time series whose records have shape dims, chunked
    !! by `chunk_records` records (default 1024) and kept open for appends.
    !! Its chunk cache is small: appends of whole blocks go straight to disk.
    subroutine h5_series(me, path, dims, chunk_records)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path               !! dataset
        integer, intent(in) :: dims(:)                     !! shape of one record
        integer, intent(in), optional :: chunk_records     !! records per chunk
        integer(hsize_t) :: cur(size(dims) + 1), mx(size(dims) + 1), chunk(size(dims) + 1)
        integer(hid_t) :: space, dset, dcpl, dapl
        integer :: err, r, rec, nrec
        type(series_t), allocatable :: tmp(:)
        if (me%stat /= stat_ok) return
        r = size(dims) + 1
        if (r > max_rank) then
            call fail(me, 'writing '//me%final_name//' failed: series '//path//' has too many dimensions')
            return
        end if
        nrec = 1024
        if (present(chunk_records)) nrec = max(1, chunk_records)
        cur(1:r - 1) = int(dims, hsize_t); cur(r) = 0
        mx(1:r - 1) = int(dims, hsize_t); mx(r) = H5S_UNLIMITED_F
        where (cur(1:r - 1) == 0) mx(1:r - 1) = H5S_UNLIMITED_F   ! empty records: chunk dims must be >= 1
        rec = max(1, product(dims))
        chunk(1:r - 1) = max(1_hsize_t, int(dims, hsize_t))
        ! at most about 1 MiB a chunk
        chunk(r) = int(max(1, min(nrec, 131072/rec)), hsize_t)
        call h5screate_simple_f(r, cur, space, err, mx)
        call check(me, err, 'dataspace of '//path)
        if (me%stat /= stat_ok) return
        call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl, err)
        call check(me, err, 'properties of '//path)
        call h5pset_chunk_f(dcpl, r, chunk, err)
        call check(me, err, 'chunks of '//path)
        call h5pcreate_f(H5P_DATASET_ACCESS_F, dapl, err)
        call check(me, err, 'properties of '//path)
        call h5pset_chunk_cache_f(dapl, 17_size_t, int(8*rec*chunk(r) + 1024, size_t), 1.0, err)
        call check(me, err, 'chunk cache of '//path)
        if (me%stat == stat_ok) then
            call h5dcreate_f(me%id, path, H5T_NATIVE_DOUBLE, space, dset, err, dcpl, dapl_id=dapl)
            call check(me, err, 'creating '//path)
        end if
        call h5pclose_f(dcpl, err)
        call h5pclose_f(dapl, err)
        call h5sclose_f(space, err)
        if (me%stat /= stat_ok) return
        if (.not. allocated(me%ser)) allocate (me%ser(32))
        if (me%nser == size(me%ser)) then
            allocate (tmp(2*size(me%ser)))
            tmp(1:me%nser) = me%ser(1:me%nser)
            call move_alloc(tmp, me%ser)
        end if
        me%nser = me%nser + 1
        me%ser(me%nser)%path = path
        me%ser(me%nser)%dset = dset
        me%ser(me%nser)%rank = r
        me%ser(me%nser)%dims = 0
        me%ser(me%nser)%dims(1:r) = cur
    end subroutine h5_series

    !> Append `nrec` records (default 1) to the time series `path`.
    subroutine h5_append(me, path, buf, nrec)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path            !! series
        real(wp), intent(in), target :: buf(*)          !! nrec records, Fortran order
        integer, intent(in), optional :: nrec           !! number of records
        integer(hid_t) :: fspace, mspace
        integer(hsize_t) :: start(max_rank), cnt(max_rank), nr
        integer :: err, r, k
        if (me%stat /= stat_ok) return
        nr = 1
        if (present(nrec)) nr = int(nrec, hsize_t)
        if (nr < 1) return
        k = find_series(me, path)
        if (k == 0) then
            call fail(me, 'writing '//me%final_name//' failed: no series '//path)
            return
        end if
        associate (s => me%ser(k))
            r = s%rank
            s%dims(r) = s%dims(r) + nr
            call h5dset_extent_f(s%dset, s%dims(1:r), err)
            call check(me, err, 'extending '//path)
            if (me%stat /= stat_ok) return
            if (product(s%dims(1:r - 1)) == 0) return
            call h5dget_space_f(s%dset, fspace, err)
            call check(me, err, 'dataspace of '//path)
            if (me%stat /= stat_ok) return
            start(1:r) = 0; start(r) = s%dims(r) - nr
            cnt(1:r) = s%dims(1:r); cnt(r) = nr
            call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, start(1:r), cnt(1:r), err)
            call check(me, err, 'selecting in '//path)
            call h5screate_simple_f(r, cnt(1:r), mspace, err)
            call check(me, err, 'dataspace of '//path)
            if (me%stat == stat_ok) then
                call h5dwrite_f(s%dset, H5T_NATIVE_DOUBLE, c_loc(buf), err, mspace, fspace)
                call check(me, err, 'writing '//path)
                call h5sclose_f(mspace, err)
            end if
            call h5sclose_f(fspace, err)
        end associate
    end subroutine h5_append

    !> Index of the open series `path` (0 if none); series are appended in
    !! the order they were created, so the next one is tried first.
    integer function find_series(me, path) result(k)
        class(h5_file_t), intent(inout) :: me
        character(len=*), intent(in) :: path
        integer :: j
        do j = 0, me%nser - 1
            k = 1 + mod(me%last + j, me%nser)
            if (me%ser(k)%path == path) then
                me%last = k
                return
            end if
        end do
        k = 0
    end function find_series

    !> Flush everything written so far to disk.
    subroutine h5_flush(me)
        class(h5_file_t), intent(inout) :: me
        integer :: err
        if (.not. me%is_open .or. me%stat /= stat_ok) return
        call h5fflush_f(me%id, H5F_SCOPE_GLOBAL_F, err)
        call check(me, err, 'flushing')
    end subroutine h5_flush

end module hn_h5
