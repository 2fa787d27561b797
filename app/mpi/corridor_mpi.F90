!> The model's prediction corridor: the fitted and uncertain parameters of a
!! calibration deck (its PARAM cards and bounds) spread over a Latin
!! hypercube (its FIT card: number of members and seed), every member run
!! on every case, and the model's point-wise mean and SD of each rated head
!! channel against the volunteers' mean: the share of the window in which
!! the volunteers' mean lies inside the model's mean +- 1 SD.
!!
!!   FPM_FC=mpifort fpm run --profile release --flag -DHHNECK_MPI --example corridor_mpi --runner echo
!!   mpirun -np 2 EXE input/corridor_nbdl.inp OUT_PREFIX
!!
!! Members are dealt round-robin to the ranks and gathered by a sum on rank
!! 0 (each member's histories are nonzero on one rank only). Built without
!! -DHHNECK_MPI it runs the members serially. Writes OUT_PREFIX_SEV.csv
!! (t, then per channel model mean, model SD, volunteer mean, volunteer SD)
!! for hhneck-plot-corridor and prints the coverage table.
program corridor_mpi
#ifdef HHNECK_MPI
    use mpi
#endif
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
    use hn_kinds, only: wp, msglen
    use hn_case, only: path_len
    use hn_sweep, only: sweep_design
    use hn_calibrate, only: calibration_t, read_calibration, member_histories
    use hn_strings, only: path_stem
    implicit none
    type(calibration_t) :: cal
    character(len=path_len) :: deck, prefix
    character(len=msglen) :: msg
    real(wp), allocatable :: v(:, :), y(:, :, :, :), ysum(:, :, :, :), ok(:), oksum(:), mean(:, :), sd(:, :)
    integer :: rank, nranks, ierr, stat, r, c, k, nt, nc, nm, u, i, nok, nwin, nrated
    logical :: good, inside(1)
    real(wp) :: cover
    rank = 0; nranks = 1
#ifdef HHNECK_MPI
    call mpi_init(ierr)
    call mpi_comm_rank(MPI_COMM_WORLD, rank, ierr)
    call mpi_comm_size(MPI_COMM_WORLD, nranks, ierr)
#endif
    if (command_argument_count() < 2) then
        if (rank == 0) write (error_unit, '(a)') 'usage: corridor_mpi CALIBRATION_DECK OUT_PREFIX'
        call finish(1)
    end if
    call get_command_argument(1, deck)
    call get_command_argument(2, prefix)
    call read_calibration(trim(deck), trim(deck), cal, stat, msg)
    if (stat /= 0) then
        if (rank == 0) write (error_unit, '(a)') 'corridor_mpi: '//trim(msg)
        call finish(2)
    end if
    v = sweep_design(cal%sw(1))                    ! LHS: FIT members and seed
    nm = size(v, 2); nc = size(cal%sw); nt = size(cal%vol(1)%t); nrated = size(cal%channels)
    allocate (y(nt, nrated, nc, nm), ok(nm))
    y = 0; ok = 0
    do r = 1 + rank, nm, nranks
        call member_histories(cal, v(:, r), y(:, :, :, r), good)
        if (good) ok(r) = 1
        write (error_unit, '(a,i0,a,i0,a,i0,a,l1)') 'corridor_mpi: rank ', rank, ' member ', r, ' of ', nm, &
            ' complete ', good
    end do
    allocate (ysum(nt, nrated, nc, nm), oksum(nm))
#ifdef HHNECK_MPI
    call mpi_reduce(y, ysum, size(y), MPI_DOUBLE_PRECISION, MPI_SUM, 0, MPI_COMM_WORLD, ierr)
    call mpi_reduce(ok, oksum, nm, MPI_DOUBLE_PRECISION, MPI_SUM, 0, MPI_COMM_WORLD, ierr)
#else
    ysum = y; oksum = ok
#endif
    if (rank == 0) then
        nok = count(oksum > 0.5_wp)
        write (output_unit, '(a,i0,a,i0,a,i0,a)') 'PREDICTION CORRIDOR: ', nok, ' of ', nm, ' members complete, ', &
            nranks, ' rank(s)'
        allocate (mean(nt, nrated), sd(nt, nrated))
        do c = 1, nc
            do k = 1, nrated
                mean(:, k) = sum(ysum(:, k, c, :), dim=2, mask=spread(oksum > 0.5_wp, 1, nt))/nok
                sd(:, k) = sqrt(sum((ysum(:, k, c, :) - spread(mean(:, k), 2, nm))**2, dim=2, &
                                    mask=spread(oksum > 0.5_wp, 1, nt))/(nok - 1))
            end do
            open (newunit=u, file=trim(prefix)//'_'//trim(path_stem(cal%decks(c)))//'.csv', status='replace', &
                  action='write')
            write (u, '(a)', advance='no') 'time_ms'
            do k = 1, nrated
                write (u, '(4(a))', advance='no') ','//trim(cal%channels(k)%name)//'_model_mean', &
                    ','//trim(cal%channels(k)%name)//'_model_sd', ','//trim(cal%channels(k)%name)//'_vol_mean', &
                    ','//trim(cal%channels(k)%name)//'_vol_sd'
            end do
            write (u, '(a)') ''
            do i = 1, nt
                write (u, '(f8.2,*(:,",",es14.6))') cal%vol(c)%t(i), (mean(i, k), sd(i, k), cal%vol(c)%mean(i, k), &
                                                                    cal%vol(c)%sd(i, k), k=1, nrated)
            end do
            close (u)
            do k = 1, nrated
                nwin = 0; cover = 0
                do i = 1, nt
                    if (cal%vol(c)%t(i) < cal%window(1) .or. cal%vol(c)%t(i) > cal%window(2)) cycle
                    nwin = nwin + 1
                    inside = abs(cal%vol(c)%mean(i, k) - mean(i, k)) <= sd(i, k)
                    if (inside(1)) cover = cover + 1
                end do
                write (output_unit, '(a,a,a10,a,f6.1,a,i0,a,i0,a)') trim(path_stem(cal%decks(c))), ' ', &
                    cal%channels(k)%name, ': volunteer mean inside the model mean +- 1 SD ', 100*cover/nwin, &
                    ' % of ', nint(cal%window(1)), '-', nint(cal%window(2)), ' ms'
            end do
        end do
    end if
    call finish(0)
contains
    subroutine finish(code)
        integer, intent(in) :: code
#ifdef HHNECK_MPI
        call mpi_finalize(ierr)
#endif
        ! quiet: no note on stderr of the floating-point flags still raised
        ! (gradual underflow in the elements' exponentials is expected)
        if (code /= 0) error stop code, quiet=.true.
        stop 0, quiet=.true.
    end subroutine finish
end program corridor_mpi
