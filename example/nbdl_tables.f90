!> Writes the TABLE cards of the NBDL 15 g sled deck from the volunteer
!! data: each run's T1 x-acceleration and T1 sagittal rotation filtered
!! CFC 60, averaged over the runs, resampled every 1 ms.
!!
!!   fpm run --example nbdl_tables -- ../shared/data/nbdl_15g tables.inp
!!
!! (the cards go to a file: fpm itself may print build progress on stdout)
program nbdl_tables
    use hn_kinds, only: wp, msglen
    use hn_filters, only: cfc_filter
    use hn_volunteer_data, only: read_runs_csv
    implicit none
    character(len=512) :: dir, outfile
    integer :: out
    dir = '../shared/data/nbdl_15g'
    outfile = 'nbdl_tables.inp'
    if (command_argument_count() >= 1) call get_command_argument(1, dir)
    if (command_argument_count() >= 2) call get_command_argument(2, outfile)
    open (newunit=out, file=trim(outfile), status='replace', action='write')
    write (out, '(a)') '* T1 x- and z-acceleration [g] and sagittal rotation [deg] of the NBDL 15 g'
    write (out, '(a)') '* runs 1635-1644 (n = 7): each run filtered CFC 60 (SAE J211/1), mean over the'
    write (out, '(a)') '* runs, every 1 ms. Written by  fpm run --example nbdl_tables  from'
    write (out, '(a)') '* ../shared/data/nbdl_15g (Ewing & Thomas 1972, NHTSA Biomechanics Test'
    write (out, '(a)') '* Database, via IMMC-UWaterloo/ARCGen). Time in ms (scale 0.001 s).'
    call table('T1XACC', trim(dir)//'/T1_XAccel.csv', '9.80665')
    call table('T1RY', trim(dir)//'/T1_YrotDisp.csv', '1.0')
    call table('T1ZACC', trim(dir)//'/T1_ZAccel.csv', '9.80665')
    close (out)
contains

    subroutine table(name, file, scale)
        character(len=*), intent(in) :: name, file, scale
        real(wp), allocatable :: t(:), runs(:, :), filt(:), mean(:)
        integer :: nrun, k, j, n, npts, stat
        character(len=msglen) :: msg
        character(len=80) :: card
        character(len=10) :: nm
        real(wp) :: v(3), tt(3)
        call read_runs_csv(file, t, runs, stat, msg)
        if (stat /= 0) error stop trim(msg)
        nrun = size(runs, 2)
        n = size(t)
        allocate (filt(n), mean(n))
        mean = 0
        do k = 1, nrun
            call cfc_filter(runs(:, k), (t(2) - t(1))*1.0e-3_wp, 60.0_wp, filt)
            mean = mean + filt/nrun
        end do
        npts = 0
        do j = 1, n
            if (abs(t(j) - nint(t(j))) < 1.0e-9_wp) npts = npts + 1
        end do
        nm = name
        write (card, '(a8,2x,a10,i10,a10,a10)') 'TABLE   ', nm, npts, '0.001', scale
        write (out, '(a)') trim(card)
        k = 0
        card = ''
        do j = 1, n
            if (abs(t(j) - nint(t(j))) > 1.0e-9_wp) cycle
            k = k + 1
            tt(k) = t(j); v(k) = mean(j)
            if (k == 3) then
                write (out, '(10x,3(f10.1,f10.4))') (tt(k), v(k), k=1, 3)
                k = 0
            end if
        end do
        if (k > 0) write (out, '(10x,3(f10.1,f10.4))') (tt(j), v(j), j=1, k)
    end subroutine table


end program nbdl_tables
