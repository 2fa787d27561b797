!> The MPI driver of parameter sweeps: the member runs of a sweep deck
!! spread over MPI ranks with dynamic load balancing, results gathered on
!! rank 0 into one listing and one HDF5 file.
!!
!!   FPM_FC=mpifort fpm build --profile release --flag -DHHNECK_MPI
!!   mpirun -np 4 $(FPM_FC=mpifort fpm run --profile release --flag -DHHNECK_MPI \
!!          --example sweep_mpi --runner echo) input/sweep_nbdl_oat.inp --h5 oat.h5
!!
!! The base deck and the INCLUDE files are looked for as by hhneck: next to
!! the including file, in the working directory, then in the directories of
!! -I DIR (repeatable) and of the environment variable HHNECK_PATH.
!!
!! (as root add --allow-run-as-root; more ranks than cores: --oversubscribe).
!! The deck is named on the command line because mpirun gives standard
!! input to rank 0 only. Every rank takes the next member number from a
!! counter in an MPI window on rank 0 (MPI_Win_allocate, MPI_Fetch_and_op
!! under a passive-target lock) whenever it is free, so long and short
!! members balance themselves; rank 0 runs members too. One rank needs no
!! counter. Built without -DHHNECK_MPI (plain `fpm build`), the same program
!! runs the members one after the other.
!!
!! Exit codes as the main program: 0 all members complete, 2 sweep deck
!! error, 4 result file not written, 6 some members failed (recorded).
program sweep_mpi
#ifdef HHNECK_MPI
    use mpi
#endif
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
    use hn_kinds, only: wp, msglen, i8
    use hn_case, only: path_len
    use hn_deck_reader, only: add_environment_path
    use hn_version, only: code_version
    use hn_run, only: exit_deck, exit_usage, exit_output, exit_members_failed
    use hn_sweep, only: sweep_t, member_record_t, read_sweep, sweep_design, run_member, nout
    use hn_sweep_report, only: sweep_finish
    implicit none
    type(sweep_t) :: sw
    type(member_record_t), allocatable :: recs(:)
    real(wp), allocatable :: v(:, :)
    character(len=path_len) :: deck, h5name, arg
    character(len=path_len), allocatable :: search(:)
    character(len=msglen) :: msg
    integer :: rank, nranks, stat, r, nrun, i, code
    logical :: h5_given, no_h5
    integer(i8) :: c0, c1, rate
    real(wp) :: wall
#ifdef HHNECK_MPI
    integer :: ierr, win
    integer(kind=MPI_ADDRESS_KIND) :: winsize, disp, baseptr
#endif

    rank = 0
    nranks = 1
#ifdef HHNECK_MPI
    call mpi_init(ierr)
    call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
    call mpi_comm_size(MPI_COMM_WORLD, nranks, ierr)
#else
    write (error_unit, '(a)') 'sweep_mpi: built without MPI (-DHHNECK_MPI); running the members serially'
#endif

    deck = ''
    h5name = ''
    h5_given = .false.
    no_h5 = .false.
    allocate (search(0))
    i = 1
    do while (i <= command_argument_count())
        call get_command_argument(i, arg)
        select case (arg)
        case ('--h5')
            i = i + 1
            call get_command_argument(i, h5name)
            h5_given = .true.
        case ('--no-h5')
            no_h5 = .true.
        case ('-I', '--include-path')
            i = i + 1
            call get_command_argument(i, arg)
            if (len_trim(arg) > 0) search = [character(len=path_len) :: search, arg]
        case default
            deck = arg
        end select
        i = i + 1
    end do
    if (len_trim(deck) == 0) then
        if (rank == 0) write (error_unit, '(a)') 'usage: sweep_mpi SWEEP_DECK [--h5 FILE | --no-h5] [-I DIR]...'
        call finish(exit_usage)
    end if

    call add_environment_path(search)   ! HHNECK_PATH after the -I directories, as hhneck
    call read_sweep(trim(deck), trim(deck), sw, stat, msg, search)
    if (stat /= 0) then
        if (rank == 0) write (error_unit, '(a)') 'sweep_mpi: sweep deck error: '//trim(msg)
        call finish(exit_deck)
    end if
    if (.not. h5_given) h5name = sw%h5file
    if (no_h5) h5name = ''
    v = sweep_design(sw)
    nrun = size(v, 2)
    allocate (recs(nrun))
    call system_clock(c0, rate)

#ifdef HHNECK_MPI
    if (nranks > 1) then
        ! the shared member counter lives in a window on rank 0
        winsize = 0
        if (rank == 0) winsize = storage_size(r)/8
        call mpi_win_allocate(winsize, storage_size(r)/8, MPI_INFO_NULL, MPI_COMM_WORLD, baseptr, win, ierr)
        call mpi_win_lock_all(0, win, ierr)
        disp = 0
        if (rank == 0) then
            r = 0
            call mpi_put(r, 1, MPI_INTEGER, 0, disp, 1, MPI_INTEGER, win, ierr)
            call mpi_win_flush(0, win, ierr)
        end if
        call mpi_barrier(MPI_COMM_WORLD, ierr)
    end if
#endif
    r = 0
    do
        r = next_member(r)
        if (r > nrun) exit
        call run_member(sw, v(:, r), recs(r))
        recs(r)%rank = rank
        write (error_unit, '(a,i0,a,i0,a,i0,a,i0,a,f7.2,a)') 'sweep_mpi: rank ', rank, ': run ', r, ' of ', nrun, &
            ': exit ', recs(r)%status, ', ', recs(r)%wall, ' s'
    end do
#ifdef HHNECK_MPI
    if (nranks > 1) then
        call mpi_win_unlock_all(win, ierr)
        call mpi_win_free(win, ierr)
    end if
    call gather_records()
#endif
    call system_clock(c1)
    wall = real(c1 - c0, wp)/real(rate, wp)

    code = 0
    if (rank == 0) then
        call sweep_finish(sw, v, recs, nranks, wall, output_unit, trim(h5name), code_version, stat, msg)
        if (stat /= 0) then
            write (error_unit, '(a)') 'sweep_mpi: '//trim(msg)
            code = exit_output
        else if (any(recs%status /= 0)) then
            write (error_unit, '(a,i0,a,i0,a)') 'sweep_mpi: sweep finished; ', count(recs%status /= 0), ' of ', &
                nrun, ' member runs failed (listed in the listing and the result file)'
            code = exit_members_failed
        else
            write (error_unit, '(a,i0,a,i0,a,f8.2,a,f8.3,a)') 'sweep_mpi: sweep finished; all ', nrun, &
                ' member runs complete on ', nranks, ' ranks in ', wall, ' s (', nrun/wall, ' runs/s)'
        end if
    end if
    call finish(code)

contains

    !> The member after `r` this rank should run: the next number of the
    !! shared counter over MPI, simply r + 1 on one rank.
    integer function next_member(r) result(next)
        integer, intent(in) :: r
#ifdef HHNECK_MPI
        if (nranks > 1) then
            call mpi_fetch_and_op(1, next, MPI_INTEGER, 0, disp, MPI_SUM, win, ierr)
            call mpi_win_flush(0, win, ierr)
            next = next + 1
            return
        end if
#endif
        next = r + 1
    end function next_member

    !> End every rank with the exit code of rank 0.
    subroutine finish(c)
        integer, intent(in) :: c
        integer :: cc
        cc = c
#ifdef HHNECK_MPI
        call mpi_bcast(cc, 1, MPI_INTEGER, 0, MPI_COMM_WORLD, ierr)
        call mpi_finalize(ierr)
#endif
        ! quiet: no note on stderr of the floating-point flags still raised
        ! (gradual underflow in the elements' exponentials is expected)
        stop cc, quiet=.true.
    end subroutine finish

#ifdef HHNECK_MPI
    !> Bring every record to rank 0: numbers by a sum over ranks (a run's
    !! numbers are nonzero on its own rank only, and x + 0 is exact), the
    !! messages of the runs that have one point to point.
    subroutine gather_records()
        real(wp), allocatable :: num(:, :), tot(:, :)
        integer, allocatable :: idx(:)
        character(len=msglen), allocatable :: msgs(:)
        integer :: k, m, src, st(MPI_STATUS_SIZE)
        allocate (num(nout + 6, nrun), tot(nout + 6, nrun))
        num = 0
        do k = 1, nrun
            if (recs(k)%status < 0) cycle           ! not run here
            num(1:nout, k) = recs(k)%outputs
            num(nout + 1, k) = recs(k)%status
            num(nout + 2, k) = recs(k)%t_reached
            num(nout + 3, k) = recs(k)%wall
            num(nout + 4, k) = recs(k)%nevals
            num(nout + 5, k) = recs(k)%rank
            num(nout + 6, k) = 1                    ! ran here
        end do
        call mpi_reduce(num, tot, size(num), MPI_DOUBLE_PRECISION, MPI_SUM, 0, MPI_COMM_WORLD, ierr)
        if (rank == 0) then
            do k = 1, nrun
                if (nint(tot(nout + 6, k)) /= 1) then
                    recs(k)%status = exit_output
                    recs(k)%message = 'the run was not carried out exactly once over the ranks (an MPI failure)'
                    cycle
                end if
                recs(k)%outputs = tot(1:nout, k)
                recs(k)%status = nint(tot(nout + 1, k))
                recs(k)%t_reached = tot(nout + 2, k)
                recs(k)%wall = tot(nout + 3, k)
                recs(k)%nevals = nint(tot(nout + 4, k))
                recs(k)%rank = nint(tot(nout + 5, k))
            end do
            do src = 1, nranks - 1
                call mpi_recv(m, 1, MPI_INTEGER, src, 1, MPI_COMM_WORLD, st, ierr)
                if (m == 0) cycle
                allocate (idx(m), msgs(m))
                call mpi_recv(idx, m, MPI_INTEGER, src, 2, MPI_COMM_WORLD, st, ierr)
                call mpi_recv(msgs, m*msglen, MPI_CHARACTER, src, 3, MPI_COMM_WORLD, st, ierr)
                recs(idx)%message = msgs
                deallocate (idx, msgs)
            end do
        else
            idx = pack([(k, k=1, nrun)], recs%status >= 0 .and. len_trim(recs%message) > 0)
            m = size(idx)
            call mpi_send(m, 1, MPI_INTEGER, 0, 1, MPI_COMM_WORLD, ierr)
            if (m > 0) then
                msgs = recs(idx)%message
                call mpi_send(idx, m, MPI_INTEGER, 0, 2, MPI_COMM_WORLD, ierr)
                call mpi_send(msgs, m*msglen, MPI_CHARACTER, 0, 3, MPI_COMM_WORLD, ierr)
            end if
        end if
    end subroutine gather_records
#endif

end program sweep_mpi
