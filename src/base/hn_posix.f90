!> The few operating-system services the program needs beyond Fortran's
!! own input/output: what kind of file a path or standard input is (so that
!! devices, FIFOs and directories are refused before they are read), a
!! terminal test, process ids for lock files, creating directories,
!! removing and renaming files, reading standard input in blocks, and the
!! async-signal-safe write and exit used by the signal handler.
!!
!! File kinds come from gfortran's STAT/FSTAT (st_mode); the rest are POSIX
!! C functions called through explicit interfaces.
module hn_posix
    use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_size_t, c_long
    use, intrinsic :: iso_fortran_env, only: input_unit
    use hn_kinds, only: i8
    implicit none
    private

    public :: file_kind, stdin_kind, kind_name, is_terminal, process_id, process_alive, host_name, &
              make_directories, remove_directory, remove_file, rename_file, read_stdin_block, raw_write_stderr, exit_now, &
              parent_directory, is_absolute, join_path

    integer, parameter, public :: kind_missing = 0, kind_regular = 1, kind_directory = 2, kind_char_device = 3, &
                                  kind_block_device = 4, kind_fifo = 5, kind_socket = 6, kind_other = 7

    interface
        function c_isatty(fd) bind(C, name='isatty') result(r)
            import :: c_int
            integer(c_int), value :: fd
            integer(c_int) :: r
        end function c_isatty
        function c_getpid() bind(C, name='getpid') result(r)
            import :: c_int
            integer(c_int) :: r
        end function c_getpid
        function c_kill(pid, sig) bind(C, name='kill') result(r)
            import :: c_int
            integer(c_int), value :: pid, sig
            integer(c_int) :: r
        end function c_kill
        function c_gethostname(name, n) bind(C, name='gethostname') result(r)
            import :: c_int, c_char, c_size_t
            character(kind=c_char), intent(out) :: name(*)
            integer(c_size_t), value :: n
            integer(c_int) :: r
        end function c_gethostname
        function c_mkdir(path, mode) bind(C, name='mkdir') result(r)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: mode
            integer(c_int) :: r
        end function c_mkdir
        function c_rmdir(path) bind(C, name='rmdir') result(r)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: r
        end function c_rmdir
        function c_unlink(path) bind(C, name='unlink') result(r)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: r
        end function c_unlink
        function c_rename(old, new) bind(C, name='rename') result(r)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: old(*), new(*)
            integer(c_int) :: r
        end function c_rename
        function c_read(fd, buf, n) bind(C, name='read') result(r)
            import :: c_int, c_char, c_size_t, c_long
            integer(c_int), value :: fd
            character(kind=c_char), intent(inout) :: buf(*)
            integer(c_size_t), value :: n
            integer(c_long) :: r
        end function c_read
        function c_write(fd, buf, n) bind(C, name='write') result(r)
            import :: c_int, c_char, c_size_t, c_long
            integer(c_int), value :: fd
            character(kind=c_char), intent(in) :: buf(*)
            integer(c_size_t), value :: n
            integer(c_long) :: r
        end function c_write
        subroutine c_exit(code) bind(C, name='_exit')
            import :: c_int
            integer(c_int), value :: code
        end subroutine c_exit
    end interface

contains

    !> Kind of file at `path` (kind_missing when there is none); symbolic
    !! links are followed.
    function file_kind(path) result(kind)
        character(len=*), intent(in) :: path   !! file name
        integer :: kind
        integer :: values(13), st
        call stat(path, values, st)
        if (st /= 0) then
            kind = kind_missing
        else
            kind = mode_kind(values(3))
        end if
    end function file_kind

    !> Kind of file standard input is (a terminal is a character device).
    function stdin_kind() result(kind)
        integer :: kind
        integer :: values(13), st
        call fstat(input_unit, values, st)
        if (st /= 0) then
            kind = kind_missing
        else
            kind = mode_kind(values(3))
        end if
    end function stdin_kind

    pure integer function mode_kind(mode) result(kind)
        integer, intent(in) :: mode
        select case (iand(mode, int(o'170000')))
        case (int(o'100000')); kind = kind_regular
        case (int(o'040000')); kind = kind_directory
        case (int(o'020000')); kind = kind_char_device
        case (int(o'060000')); kind = kind_block_device
        case (int(o'010000')); kind = kind_fifo
        case (int(o'140000')); kind = kind_socket
        case default; kind = kind_other
        end select
    end function mode_kind

    !> Words for a file kind in messages ("a directory").
    pure function kind_name(kind) result(s)
        integer, intent(in) :: kind   !! a kind_* value
        character(len=:), allocatable :: s
        select case (kind)
        case (kind_missing); s = 'missing'
        case (kind_regular); s = 'a regular file'
        case (kind_directory); s = 'a directory'
        case (kind_char_device); s = 'a character device'
        case (kind_block_device); s = 'a block device'
        case (kind_fifo); s = 'a FIFO (named pipe)'
        case (kind_socket); s = 'a socket'
        case default; s = 'a special file'
        end select
    end function kind_name

    !> True when file descriptor `fd` (0, 1, 2) is a terminal.
    logical function is_terminal(fd)
        integer, intent(in) :: fd   !! file descriptor
        is_terminal = c_isatty(int(fd, c_int)) == 1
    end function is_terminal

    !> This process's id.
    integer function process_id()
        process_id = int(c_getpid())
    end function process_id

    !> True when a process with id `pid` exists on this machine.
    logical function process_alive(pid)
        integer, intent(in) :: pid   !! process id
        character(len=24) :: proc
        process_alive = .false.
        if (pid <= 0) return
        write (proc, '(a,i0)') '/proc/', pid
        if (file_kind('/proc/self') == kind_directory) then
            process_alive = file_kind(trim(proc)) == kind_directory
        else
            process_alive = c_kill(int(pid, c_int), 0_c_int) == 0
        end if
    end function process_alive

    !> This machine's host name ('' when unknown).
    function host_name() result(s)
        character(len=:), allocatable :: s
        character(kind=c_char) :: buf(256)
        integer :: k
        buf = c_null_char
        s = ''
        if (c_gethostname(buf, int(size(buf) - 1, c_size_t)) /= 0) return
        do k = 1, size(buf)
            if (buf(k) == c_null_char) exit
            s = s//buf(k)
        end do
    end function host_name

    !> Create directory `path` and its missing parents (like mkdir -p);
    !! stat /= 0 when one cannot be created.
    subroutine make_directories(path, stat)
        character(len=*), intent(in) :: path   !! directory
        integer, intent(out) :: stat           !! 0 when the directory exists afterwards
        integer :: k, r
        stat = 0
        if (len_trim(path) == 0) return
        do k = 2, len_trim(path) + 1
            if (k <= len_trim(path)) then
                if (path(k:k) /= '/') cycle
            end if
            if (file_kind(path(1:k - 1)) == kind_directory) cycle
            r = c_mkdir(path(1:k - 1)//c_null_char, int(o'777', c_int))
            if (file_kind(path(1:k - 1)) /= kind_directory) then
                stat = 1
                return
            end if
        end do
    end subroutine make_directories

    !> Remove the empty directory `path`; stat /= 0 when it could not be removed.
    subroutine remove_directory(path, stat)
        character(len=*), intent(in) :: path   !! directory
        integer, intent(out) :: stat           !! 0 on success
        stat = int(c_rmdir(path//c_null_char))
    end subroutine remove_directory

    !> Remove file `path`; stat /= 0 when it could not be removed.
    subroutine remove_file(path, stat)
        character(len=*), intent(in) :: path   !! file name
        integer, intent(out) :: stat           !! 0 on success
        stat = int(c_unlink(path//c_null_char))
    end subroutine remove_file

    !> Rename `old` to `new` (atomically replacing `new`); stat /= 0 on failure.
    subroutine rename_file(old, new, stat)
        character(len=*), intent(in) :: old        !! file name now (trailing blanks are part of it)
        character(len=*), intent(in) :: new        !! file name after (replaced when it exists)
        integer, intent(out) :: stat               !! 0 on success
        stat = int(c_rename(old//c_null_char, new//c_null_char))
    end subroutine rename_file

    !> Read up to len(buf) bytes of standard input (file descriptor 0) into
    !! buf; n = bytes read, 0 at the end, -1 on an error.
    subroutine read_stdin_block(buf, n)
        character(len=*), intent(inout) :: buf   !! buffer
        integer(i8), intent(out) :: n            !! bytes read
        n = int(c_read(0_c_int, buf, int(len(buf), c_size_t)), i8)
    end subroutine read_stdin_block

    !> Write text to standard error without Fortran I/O (safe in a signal handler).
    subroutine raw_write_stderr(text)
        character(len=*), intent(in) :: text   !! bytes to write
        integer(c_long) :: r
        r = c_write(2_c_int, text, int(len(text), c_size_t))
    end subroutine raw_write_stderr

    !> End the process at once with `code` (no Fortran clean-up; safe in a signal handler).
    subroutine exit_now(code)
        integer, intent(in) :: code   !! exit code
        call c_exit(int(code, c_int))
    end subroutine exit_now

    !> Directory part of a path ('' when it has none; '/' for the root).
    pure function parent_directory(path) result(d)
        character(len=*), intent(in) :: path   !! file name
        character(len=:), allocatable :: d
        integer :: k
        k = index(trim(path), '/', back=.true.)
        if (k == 0) then
            d = ''
        else if (k == 1) then
            d = '/'
        else
            d = path(1:k - 1)
        end if
    end function parent_directory

    !> True for a path that starts at the root.
    pure logical function is_absolute(path)
        character(len=*), intent(in) :: path   !! file name
        is_absolute = .false.
        if (len(path) > 0) is_absolute = path(1:1) == '/'
    end function is_absolute

    !> dir/name ('name' when dir is empty).
    pure function join_path(dir, name) result(p)
        character(len=*), intent(in) :: dir    !! directory ('' for none; trailing blanks ignored)
        character(len=*), intent(in) :: name   !! file name (trailing blanks ignored)
        character(len=:), allocatable :: p
        if (len_trim(dir) == 0) then
            p = trim(name)
        else if (dir(len_trim(dir):len_trim(dir)) == '/') then
            p = trim(dir)//trim(name)
        else
            p = trim(dir)//'/'//trim(name)
        end if
    end function join_path

end module hn_posix
