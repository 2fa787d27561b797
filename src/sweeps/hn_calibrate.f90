!> Calibration as code: fit named deck parameters (the PARAM cards of the
!! sweep deck: FAMILY scale factors, BODY scales, FIELDn values), within
!! their bounds, to the NBDL volunteers of one or more cases, by minimising
!!
!!   J = (1 - R) + w P + wt T,
!!
!! R the mean CORA-style rating of the five head kinematic channels over the
!! cases (x- and z-acceleration, angular acceleration, angular velocity,
!! rotation; the rating of tools/compare_nbdl.py, docs/validation.md), P the
!! mean over the cases' six head peaks of max(0, |z| - (1 - m)), z the peak's
!! distance from the volunteers' mean in SDs and m a margin inside the
!! 1 SD band, T the mean over the same peaks of max(0, |dt|/10 ms - (1 - m)),
!! dt the peak time's distance from the volunteers' mean time (the same
!! margin keeps the times off the 10 ms edge); w (default
!! 0.02), wt (default 0) and m (default 0) are fields 5, 6 and 7 of the FIT
!! card; subject to the
!! model standing at rest: a parameter set whose start state (posture held,
!! the bracing activation) has an eigenvalue with real part above -1 1/s
!! in any case (hn_rest_modes) is not run and gets J = 2 + 0.1 s (lmax + 1);
!! with a PASSIVE card, nor is a set whose neck stands without its muscles
!! (largest real part at rest, muscles off, below the card's limit, default
!! 0: the osteoligamentous column buckles under far less than the head's
!! weight), which gets J = 2 + 0.1 s (limit - lp).
!! Optimizer: a Latin hypercube of starting points (seeded) and Nelder-Mead
!! from the best of them, restarted about its best point while a restart
!! gains more than 1e-4, in the unit cube of the parameter ranges (LOG
!! ranges in logarithms), points clamped to the bounds. Deterministic: the
!! same deck gives the same fit on every machine. Member runs are those of
!! the sweep (sweep_member_case, run_state_t).
module hn_calibrate
    use hn_kinds, only: wp, zero, one, msglen
    use hn_status, only: stat_ok, stat_bad_input
    use hn_case, only: case_t, deck_line_t, path_len
    use hn_deck_reader, only: deck_reader_t, read_card_images, int_str
    use hn_sweep, only: sweep_t, sweep_param_t, read_sweep_lines, sweep_member_case, sweep_design, spread_value, &
                        field_text, par_field
    use hn_run, only: run_state_t, run_result_t, exit_ok
    use hn_channels, only: channel_set_t, channels_define
    use hn_filters, only: cfc_filter
    use hn_sorting, only: sort_index
    use hn_rest_modes, only: rest_mode_t, rest_modes
    use hn_model, only: fam_muscles
    implicit none
    private

    public :: volunteer_t, read_volunteers, cora_rating, score_t, score_samples, calibration_t, read_calibration, &
              calibrate, evaluate, nelder_mead, restarted_nelder_mead, objective_fn, member_histories, rated_histories, &
              read_runs_csv

    integer, parameter, public :: nrated = 5, npeaks = 6
    character(len=10), parameter, public :: rated_channels(nrated) = [character(len=10) :: 'HEAD_AX', 'HEAD_AZ', &
        'HEAD_ALPHY', 'HEAD_OMEGY', 'HEAD_THETY']
    character(len=16), parameter, public :: peak_names(npeaks) = [character(len=16) :: 'X-ACCEL', 'Z-ACCEL DIP', &
        'Z-ACCEL REBOUND', 'ANG. ACCEL', 'ANG. VELOCITY', 'ROTATION']
    integer, parameter :: peak_channel(npeaks) = [1, 2, 2, 3, 4, 5]
    real(wp), parameter :: peak_sign(npeaks) = [-1, -1, 1, 1, 1, 1]
    real(wp), parameter :: peak_window(2, npeaks) = reshape([30.0_wp, 250.0_wp, 30.0_wp, 125.0_wp, 125.0_wp, &
        250.0_wp, 30.0_wp, 250.0_wp, 30.0_wp, 250.0_wp, 30.0_wp, 250.0_wp], [2, npeaks])   !! [ms]
    real(wp), parameter :: window(2) = [30.0_wp, 250.0_wp]   !! rating window [ms]
    real(wp), parameter :: time_tolerance = 10.0_wp          !! peak-time tolerance of the goal [ms]
    real(wp), parameter :: failed_objective = 10.0_wp        !! J of a parameter set whose run fails
    real(wp), parameter :: rest_margin = -1.0_wp             !! largest real part allowed at rest [1/s]
    real(wp), parameter :: unstable_objective = 2.0_wp       !! J of a set unstable at rest, at the margin
    real(wp), parameter :: unstable_slope = 0.1_wp           !! its growth per 1/s beyond the margin [s]

    !> The volunteers of one case, CFC 60: point-wise mean and SD of the
    !! rated channels and the mean and SD of the runs' peaks and times.
    type :: volunteer_t
        real(wp), allocatable :: t(:)               !! [ms]
        real(wp), allocatable :: mean(:, :), sd(:, :)   !! (nt, nrated)
        real(wp) :: peak_mean(npeaks) = zero, peak_sd(npeaks) = zero
        real(wp) :: time_mean(npeaks) = zero, time_sd(npeaks) = zero
        integer :: nrun = 0
    end type volunteer_t

    !> How a run compares with the volunteers.
    type :: score_t
        real(wp) :: rating(nrated) = zero           !! CORA-style rating per channel
        real(wp) :: corridor(nrated) = zero, xcorr(nrated) = zero
        real(wp) :: peak(npeaks) = zero, time(npeaks) = zero   !! model peaks [channel units, ms]
        real(wp) :: z(npeaks) = zero                !! (peak - mean)/SD
    end type score_t

    !> A calibration: its cases (deck, volunteers, the sweep that binds the
    !! parameters to that deck) and the optimizer's settings.
    type :: calibration_t
        character(len=80) :: title = ''
        character(len=path_len), allocatable :: decks(:), data(:)
        type(sweep_t), allocatable :: sw(:)
        type(volunteer_t), allocatable :: vol(:)
        integer :: max_evals = 200, nstart = 8, seed = 1
        real(wp) :: peak_weight = 0.02_wp           !! w of the objective (FIT F5)
        real(wp) :: time_weight = zero              !! wt of the objective (FIT F6)
        real(wp) :: peak_margin = zero              !! m of the objective: P counts |z| above 1 - m (FIT F7)
        logical :: passive = .false.                !! PASSIVE card: the neck without its muscles must not stand
        real(wp) :: passive_limit = zero            !! its largest real part at rest must be above this (PASSIVE F1) [1/s]
        real(wp), allocatable :: values(:)          !! VALUES cards: the point scored when max_evals = 0
    end type calibration_t

    abstract interface
        !> An objective on the unit cube.
        function objective_fn(u) result(f)
            import :: wp
            real(wp), intent(in) :: u(:)             !! point in the unit cube
            real(wp) :: f
        end function objective_fn
    end interface

contains

    !> Read the volunteer runs of directory `dir` (CHANNEL.csv as in
    !! reference/nbdl_15g) filtered CFC 60: mean, SD and peaks.
    subroutine read_volunteers(dir, vd, stat, errmsg)
        character(len=*), intent(in) :: dir    !! data directory
        type(volunteer_t), intent(out) :: vd     !! the volunteers: times, mean, SD, peaks
        integer, intent(out) :: stat             !! stat_ok, or stat_bad_input for a missing or bad file
        character(len=msglen), intent(out) :: errmsg !! what failed
        character(len=16), parameter :: files(4) = [character(len=16) :: 'Head_XAccel', 'Head_ZAccel', &
                                                    'Head_YrotAccel', 'Head_YrotDisp']
        real(wp), allocatable :: t(:), runs(:, :), ch(:, :, :)
        real(wp) :: dt
        integer :: f, r, nt, k, p
        real(wp) :: pk(2)
        real(wp), allocatable :: pks(:, :)
        do f = 1, 4
            call read_runs_csv(trim(dir)//'/'//trim(files(f))//'.csv', t, runs, stat, errmsg)
            if (stat /= stat_ok) return
            if (f == 1) then
                nt = size(t); vd%nrun = size(runs, 2); vd%t = t
                allocate (ch(nt, vd%nrun, nrated))
                dt = (t(2) - t(1))*1.0e-3_wp
            end if
            if (size(t) /= nt .or. size(runs, 2) /= vd%nrun) then
                stat = stat_bad_input
                errmsg = trim(dir)//'/'//trim(files(f))//'.csv: not the runs and times of Head_XAccel.csv'
                return
            end if
            do r = 1, vd%nrun
                call cfc_filter(runs(:, r), dt, 60.0_wp, ch(:, r, min(f, 5)))
            end do
        end do
        ! rotation in column 5; angular velocity (rad/s) its derivative in column 4
        do r = 1, vd%nrun
            ch(:, r, 5) = ch(:, r, 4)
            ch(:, r, 4) = gradient(ch(:, r, 5)*acos(-one)/180.0_wp, dt)
        end do
        allocate (vd%mean(nt, nrated), vd%sd(nt, nrated), pks(2, vd%nrun))
        do k = 1, nrated
            vd%mean(:, k) = sum(ch(:, :, k), dim=2)/vd%nrun
            vd%sd(:, k) = sqrt(sum((ch(:, :, k) - spread(vd%mean(:, k), 2, vd%nrun))**2, dim=2)/(vd%nrun - 1))
        end do
        do p = 1, npeaks
            do r = 1, vd%nrun
                pk = peak_in(vd%t, ch(:, r, peak_channel(p)), peak_sign(p), peak_window(:, p))
                pks(:, r) = pk
            end do
            vd%peak_mean(p) = sum(pks(1, :))/vd%nrun
            vd%peak_sd(p) = sqrt(sum((pks(1, :) - vd%peak_mean(p))**2)/(vd%nrun - 1))
            vd%time_mean(p) = sum(pks(2, :))/vd%nrun
            vd%time_sd(p) = sqrt(sum((pks(2, :) - vd%time_mean(p))**2)/(vd%nrun - 1))
        end do
    end subroutine read_volunteers

    !> Derivative by central differences, one-sided at the ends (numpy.gradient).
    pure function gradient(x, dt) result(d)
        real(wp), intent(in) :: x(:), dt
        real(wp) :: d(size(x))
        integer :: n
        n = size(x)
        d(2:n - 1) = (x(3:n) - x(1:n - 2))/(2*dt)
        d(1) = (x(2) - x(1))/dt
        d(n) = (x(n) - x(n - 1))/dt
    end function gradient

    !> Signed extreme of x (sign +1: maximum, -1: minimum) within [w(1), w(2)] ms, and its time.
    pure function peak_in(t, x, sgn, w) result(pk)
        real(wp), intent(in) :: t(:), x(:), sgn, w(2)
        real(wp) :: pk(2)
        integer :: i, ibest
        ibest = 0
        do i = 1, size(t)
            if (t(i) < w(1) .or. t(i) > w(2)) cycle
            if (ibest == 0) then
                ibest = i
            else if (sgn*x(i) > sgn*x(ibest)) then
                ibest = i
            end if
        end do
        pk = [x(ibest), t(ibest)]
    end function peak_in

    !> CORA-style rating of y against the volunteers' mean r and SD s on the
    !! window (docs/validation.md): corridor rating c, cross-correlation
    !! rating x, rating (c + x)/2, lag [ms].
    pure subroutine cora_rating(t, y, r, s, c, x, rating, lag)
        real(wp), intent(in) :: t(:)             !! times [ms]
        real(wp), intent(in) :: y(:)             !! the model
        real(wp), intent(in) :: r(:)             !! the volunteers' mean
        real(wp), intent(in) :: s(:)             !! their SD
        real(wp), intent(out) :: c               !! corridor rating
        real(wp), intent(out) :: x               !! cross-correlation rating
        real(wp), intent(out) :: rating          !! CORA-style rating (c + x)/2
        real(wp), intent(out) :: lag             !! lag of the best correlation [ms]
        logical :: m(size(t))
        real(wp), allocatable :: yw(:), rw(:), sw(:), inner(:), outer(:), d(:), cs(:)
        real(wp) :: floor, dt, best, rho, ep, ev, es, shift
        integer :: n, k, maxlag, lo, hi, kbest
        m = t >= window(1) .and. t <= window(2)
        yw = pack(y, m); rw = pack(r, m); sw = pack(s, m)
        n = size(yw)
        floor = 0.05_wp*maxval(abs(rw))
        inner = max(sw, floor)
        outer = max(3*sw, 3*floor)
        d = abs(yw - rw)
        allocate (cs(n))
        where (d <= inner)
            cs = one
        elsewhere (d >= outer)
            cs = zero
        elsewhere
            cs = ((outer - d)/(outer - inner))**2
        end where
        c = sum(cs)/n
        dt = t(2) - t(1)
        maxlag = nint(30.0_wp/dt)
        best = -2; kbest = 0
        do k = -maxlag, maxlag
            lo = max(0, k); hi = n + min(0, k)
            rho = pearson(yw(lo - k + 1:hi - k), rw(lo + 1:hi))
            if (rho > best) then
                best = rho; kbest = k
            end if
        end do
        shift = abs(kbest)*dt
        ep = one
        if (shift > 2.0_wp) ep = max(zero, (30.0_wp - shift)/(30.0_wp - 2.0_wp))
        ev = ((one + best)/2)**2
        es = min(sum(yw**2), sum(rw**2))/max(sum(yw**2), sum(rw**2))
        x = (ep + ev + es)/3
        rating = 0.5_wp*c + 0.5_wp*x
        lag = kbest*dt
    end subroutine cora_rating

    pure real(wp) function pearson(a, b) result(rho)
        real(wp), intent(in) :: a(:), b(:)
        real(wp) :: da(size(a)), db(size(b))
        da = a - sum(a)/size(a)
        db = b - sum(b)/size(b)
        rho = sum(da*db)/sqrt(sum(da**2)*sum(db**2))
    end function pearson

    !> Score a run's samples (channels by name, samples every dt from t0 [s])
    !! against the volunteers: each rated channel CFC 60, linearly
    !! interpolated to the volunteers' times.
    subroutine score_samples(vd, names, t0, dt, samples, sc)
        type(volunteer_t), intent(in) :: vd      !! the volunteers
        character(len=*), intent(in) :: names(:)     !! channel names of the rows of samples
        real(wp), intent(in) :: t0               !! first sample time [s]
        real(wp), intent(in) :: dt               !! sample interval [s]
        real(wp), intent(in) :: samples(:, :)        !! (nchannel, nsample)
        type(score_t), intent(out) :: sc         !! ratings and peaks
        call score_histories(vd, rated_histories(vd, names, t0, dt, samples), sc)
    end subroutine score_samples

    !> Score the rated channels y (CFC 60, at the volunteers' times) against the volunteers.
    subroutine score_histories(vd, y, sc)
        type(volunteer_t), intent(in) :: vd
        real(wp), intent(in) :: y(:, :)              !! (nt, nrated)
        type(score_t), intent(out) :: sc
        real(wp) :: lag, pk(2)
        integer :: k, p
        do k = 1, nrated
            call cora_rating(vd%t, y(:, k), vd%mean(:, k), vd%sd(:, k), sc%corridor(k), sc%xcorr(k), &
                             sc%rating(k), lag)
        end do
        do p = 1, npeaks
            pk = peak_in(vd%t, y(:, peak_channel(p)), peak_sign(p), peak_window(:, p))
            sc%peak(p) = pk(1); sc%time(p) = pk(2)
            sc%z(p) = (pk(1) - vd%peak_mean(p))/vd%peak_sd(p)
        end do
    end subroutine score_histories

    !> The rated channels of a run, CFC 60, at the volunteers' times.
    function rated_histories(vd, names, t0, dt, samples) result(y)
        type(volunteer_t), intent(in) :: vd      !! the volunteers
        character(len=*), intent(in) :: names(:)     !! channel names of the rows of samples
        real(wp), intent(in) :: t0               !! first sample time [s]
        real(wp), intent(in) :: dt               !! sample interval [s]
        real(wp), intent(in) :: samples(:, :)        !! (nchannel, nsample)
        real(wp) :: y(size(vd%t), nrated)
        real(wp) :: f(size(samples, 2)), tm(size(samples, 2))
        integer :: k, i
        do i = 1, size(tm)
            tm(i) = 1000*(t0 + (i - 1)*dt)
        end do
        do k = 1, nrated
            call cfc_filter(samples(findloc(names, rated_channels(k), dim=1), :), dt, 60.0_wp, f)
            y(:, k) = interp(vd%t, tm, f)
        end do
    end function rated_histories

    !> Run every case of the calibration at parameter values v: the rated
    !! channels at the volunteers' times, y(:, :, case); ok false when a run fails.
    subroutine member_histories(cal, v, y, ok)
        type(calibration_t), intent(in) :: cal   !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp), intent(out) :: y(:, :, :)          !! (nt, nrated, ncase)
        logical, intent(out) :: ok               !! every run complete
        type(case_t) :: cs
        type(run_result_t) :: res
        type(channel_set_t) :: ch
        integer :: c, stat, lu
        character(len=msglen) :: msg
        ok = .true.
        y = zero
        do c = 1, size(cal%sw)
            call sweep_member_case(cal%sw(c), v, cs, stat, msg)
            if (stat /= stat_ok) then
                ok = .false.; return
            end if
            open (newunit=lu, file='/dev/null', action='write')
            block
                type(run_state_t) :: run         ! a fresh run object for every case
                call run%execute(cs, lu, '', res, keep_samples=.true.)
            end block
            close (lu)
            if (res%exit_code /= exit_ok) then
                ok = .false.; return
            end if
            call channels_define(cs, ch)
            y(1:size(cal%vol(c)%t), :, c) = rated_histories(cal%vol(c), ch%name, cs%t_start, cs%sample_dt, res%samples)
        end do
    end subroutine member_histories

    !> Linear interpolation of (xp, fp) at x, end values held (numpy.interp).
    pure function interp(x, xp, fp) result(f)
        real(wp), intent(in) :: x(:), xp(:), fp(:)
        real(wp) :: f(size(x))
        integer :: i, j
        j = 1
        do i = 1, size(x)
            if (x(i) <= xp(1)) then
                f(i) = fp(1)
            else if (x(i) >= xp(size(xp))) then
                f(i) = fp(size(fp))
            else
                do while (xp(j + 1) < x(i))
                    j = j + 1
                end do
                f(i) = fp(j) + (fp(j + 1) - fp(j))*(x(i) - xp(j))/(xp(j + 1) - xp(j))
            end if
        end do
    end function interp

    !> Read a CSV file with a header line: first column time, then one column per run.
    subroutine read_runs_csv(file, t, runs, stat, errmsg)
        character(len=*), intent(in) :: file               !! the file
        real(wp), allocatable, intent(out) :: t(:)         !! first column
        real(wp), allocatable, intent(out) :: runs(:, :)   !! (row, run) the other columns
        integer, intent(out) :: stat                       !! stat_ok or stat_bad_input
        character(len=msglen), intent(out) :: errmsg       !! what went wrong
        character(len=8192) :: line
        integer :: u, ios, ncol, nrow, k
        real(wp), allocatable :: row(:)
        stat = stat_ok; errmsg = ''
        open (newunit=u, file=file, status='old', action='read', iostat=ios)
        if (ios /= 0) then
            stat = stat_bad_input; errmsg = 'cannot open volunteer data '//file
            return
        end if
        read (u, '(a)') line
        ncol = 1 + count([(line(k:k) == ',', k=1, len_trim(line))])
        nrow = 0
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (len_trim(line) > 0) nrow = nrow + 1
        end do
        rewind (u)
        read (u, '(a)') line
        allocate (t(nrow), runs(nrow, ncol - 1), row(ncol))
        do k = 1, nrow
            read (u, *, iostat=ios) row
            if (ios /= 0) then
                stat = stat_bad_input
                write (errmsg, '(3a,i0,a,i0,a)') 'volunteer data ', file, ' line ', k + 1, ': expected ', ncol, &
                    ' numbers'
                close (u)
                return
            end if
            t(k) = row(1)
            runs(k, :) = row(2:)
        end do
        close (u)
    end subroutine read_runs_csv

    !> Read a calibration deck: TITLE; CASE path (columns 11-80) followed by
    !! DATA directory of that case's volunteers; FIT NELDER max-evaluations
    !! starting-points seed [peak-weight [peak-time-weight [peak-margin]]];
    !! PARAM cards as in a sweep deck; optional PASSIVE [limit] (a set whose
    !! neck stands without its muscles is not run); optional VALUES
    !! cards (up to 7 values each, in PARAM order), the point scored when
    !! max-evaluations is 0 (default: the decks' own values). Each case's
    !! parameters are bound to its own deck through a sweep (same checks).
    subroutine read_calibration(path, source, cal, stat, errmsg)
        character(len=*), intent(in) :: path     !! the calibration deck's file
        character(len=*), intent(in) :: source   !! its name in messages
        type(calibration_t), intent(out) :: cal  !! the calibration
        integer, intent(out) :: stat             !! stat_ok, or stat_bad_input
        character(len=msglen), intent(out) :: errmsg !! the deck line, columns and what was expected
        type(deck_reader_t) :: rd
        type(deck_line_t), allocatable :: params(:), sl(:)
        character(len=10) :: s
        integer :: i, c, nfit, f
        real(wp) :: x
        rd%top = source
        call read_card_images(rd, path, source, 0)
        allocate (cal%decks(0), cal%data(0), params(0), cal%values(0))
        nfit = 0
        do i = 1, rd%nlines
            if (rd%failed()) exit
            select case (rd%key(i))
            case ('TITLE'); cal%title = adjustl(rd%lines(i)%text(11:80))
            case ('CASE'); cal%decks = [character(len=path_len) :: cal%decks, adjustl(rd%lines(i)%text(11:80))]
            case ('DATA')
                if (size(cal%data) /= size(cal%decks) - 1) then
                    call rd%fail(rd%where(i)//' (DATA card): expected one DATA card after each CASE card')
                    exit
                end if
                cal%data = [character(len=path_len) :: cal%data, adjustl(rd%lines(i)%text(11:80))]
            case ('FIT')
                nfit = nfit + 1
                call rd%name(i, 1, 'optimizer', s)
                if (s /= 'NELDER' .and. .not. rd%failed()) call rd%fail(rd%context(i, 1, 'optimizer')// &
                                                                       ': found "'//trim(s)//'"; expected NELDER')
                call rd%int(i, 2, 'maximum evaluations', cal%max_evals, 0, 100000)
                call rd%int(i, 3, 'starting points', cal%nstart, 2, 10000)
                call rd%int(i, 4, 'seed', cal%seed, 1, 2147483646)
                call rd%real(i, 5, 'peak weight', '-', cal%peak_weight, zero, 1.0e3_wp, default=0.02_wp)
                call rd%real(i, 6, 'peak-time weight', '-', cal%time_weight, zero, 1.0e3_wp, default=zero)
                call rd%real(i, 7, 'peak margin', 'SD', cal%peak_margin, zero, 0.9_wp, default=zero)
            case ('PARAM'); params = [params, rd%lines(i)]
            case ('PASSIVE')
                cal%passive = .true.
                call rd%real(i, 1, 'largest real part at rest without muscles', '1/s', cal%passive_limit, &
                             -100.0_wp, 100.0_wp, default=zero)
            case ('VALUES')
                do f = 1, 7
                    if (rd%is_blank(i, f)) cycle
                    call rd%real(i, f, 'parameter value', '-', x, -1.0e30_wp, 1.0e30_wp)
                    cal%values = [cal%values, x]
                end do
            case ('END'); exit
            case default
                call rd%fail(rd%where(i)//', columns 1-8: found "'//trim(rd%key(i))// &
                             '"; expected TITLE, CASE, DATA, FIT, PARAM, PASSIVE, VALUES or END')
            end select
        end do
        if (.not. rd%failed() .and. (size(cal%decks) == 0 .or. size(cal%data) /= size(cal%decks) .or. nfit /= 1)) &
            call rd%fail(source//': expected at least one CASE card, each followed by its DATA card, and one FIT card')
        stat = rd%stat; errmsg = rd%errmsg
        if (stat /= stat_ok) return
        allocate (cal%sw(size(cal%decks)), cal%vol(size(cal%decks)))
        do c = 1, size(cal%decks)
            sl = [line_of('TITLE     '//cal%title), line_of('BASE      '//trim(cal%decks(c))), &
                  line_of('DESIGN    LHS       '//int_field(cal%nstart)//int_field(cal%seed)), params]
            call read_sweep_lines(sl, source, cal%sw(c), stat, errmsg)
            if (stat /= stat_ok) return
            call read_volunteers(trim(cal%data(c)), cal%vol(c), stat, errmsg)
            if (stat /= stat_ok) return
        end do
    contains
        function line_of(text) result(l)
            character(len=*), intent(in) :: text
            type(deck_line_t) :: l
            l%text = text
            l%source = source
            l%line = 0
        end function line_of
        function int_field(n) result(f)
            integer, intent(in) :: n
            character(len=10) :: f
            write (f, '(i0)') n
        end function int_field
    end subroutine read_calibration

    !> Largest real part of the eigenvalues at rest (hn_rest_modes: the
    !! start state of every case, posture held as the case holds it) over
    !! the cases at parameter values v [1/s], with the muscles (lmax) and,
    !! for a PASSIVE card, without them (lp; huge without the card); each
    !! case is built once for both. Huge when a case cannot be built or
    !! analysed.
    subroutine rest_growth(cal, v, lmax, lp)
        type(calibration_t), intent(in) :: cal       !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp), intent(out) :: lmax                !! with the muscles [1/s]
        real(wp), intent(out) :: lp                  !! without them [1/s]
        type(case_t) :: cs
        type(rest_mode_t), allocatable :: modes(:)
        integer :: c, stat
        character(len=msglen) :: msg
        lmax = -huge(one)
        lp = merge(-huge(one), huge(one), cal%passive)
        do c = 1, size(cal%sw)
            call sweep_member_case(cal%sw(c), v, cs, stat, msg)
            if (stat == stat_ok) call rest_modes(cs%model, cs%t_start, cs%x0, cs%xd0, cs%hold_posture, modes, stat, msg)
            if (stat /= stat_ok) then
                lmax = huge(one); return
            end if
            if (size(modes) > 0) lmax = max(lmax, modes(1)%re)
            if (.not. cal%passive) cycle
            cs%model%family_on(fam_muscles) = .false.
            call rest_modes(cs%model, cs%t_start, cs%x0, cs%xd0, cs%hold_posture, modes, stat, msg)
            if (stat /= stat_ok) then
                lp = huge(one)
            else if (size(modes) > 0 .and. lp < huge(one)) then
                lp = max(lp, modes(1)%re)
            end if
        end do
    end subroutine rest_growth

    !> Objective J and the scores of every case for parameter values v. A
    !! parameter set whose model is not stable at rest with the margin
    !! (largest real part above rest_margin in any case: a braced neck
    !! stands) is not run: J = 2 + 0.1 s (lmax - rest_margin), worse than
    !! any stable set whose w P + wt T stays below 1, and decreasing
    !! towards stability. With a PASSIVE card, nor is a set whose neck
    !! stands without its muscles (largest real part at rest below the
    !! card's limit): J = 2 + 0.1 s (limit - lp).
    subroutine evaluate(cal, v, j, sc, ok, growth, passive_growth)
        type(calibration_t), intent(in) :: cal       !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp), intent(out) :: j                   !! the objective
        type(score_t), intent(out) :: sc(:)          !! (ncase)
        logical, intent(out) :: ok                   !! every run complete
        real(wp), intent(out), optional :: growth    !! largest real part at rest over the cases [1/s]
        real(wp), intent(out), optional :: passive_growth !! the same without the muscles (PASSIVE card) [1/s]
        real(wp), allocatable :: y(:, :, :)
        real(wp) :: rsum, psum, tsum, lmax, lp
        integer :: c
        call rest_growth(cal, v, lmax, lp)
        if (present(growth)) growth = lmax
        if (present(passive_growth)) passive_growth = huge(one)
        if (lmax > rest_margin) then
            ok = .false.
            j = rest_penalty(lmax - rest_margin)
            return
        end if
        if (cal%passive) then
            if (present(passive_growth)) passive_growth = lp
            if (lp < cal%passive_limit) then
                ok = .false.
                j = rest_penalty(cal%passive_limit - lp)
                return
            end if
        end if
        allocate (y(maxval([(size(cal%vol(c)%t), c=1, size(cal%vol))]), nrated, size(cal%sw)))
        call member_histories(cal, v, y, ok)
        j = failed_objective
        if (.not. ok) return
        rsum = zero; psum = zero; tsum = zero
        do c = 1, size(cal%sw)
            call score_histories(cal%vol(c), y(1:size(cal%vol(c)%t), :, c), sc(c))
            rsum = rsum + sum(sc(c)%rating)/nrated
            psum = psum + sum(max(zero, abs(sc(c)%z) - (one - cal%peak_margin)))/npeaks
            tsum = tsum + sum(max(zero, abs(sc(c)%time - cal%vol(c)%time_mean)/time_tolerance - &
                                  (one - cal%peak_margin)))/npeaks
        end do
        j = (one - rsum/size(cal%sw)) + (cal%peak_weight*psum + cal%time_weight*tsum)/size(cal%sw)
    end subroutine evaluate

    !> J of a parameter set that fails a check at rest by `excess` [1/s]:
    !! 2 + 0.1 s excess, worse than any set that passes, and decreasing
    !! towards the check's limit.
    pure real(wp) function rest_penalty(excess) result(j)
        real(wp), intent(in) :: excess
        j = min(failed_objective, unstable_objective + unstable_slope*excess)
    end function rest_penalty

    !> Nelder-Mead on the unit cube from u0 with initial steps `step`;
    !! points clamped to [0, 1]; stops after max_evals evaluations or when
    !! the simplex's objective values agree within ftol.
    subroutine nelder_mead(f, u0, step, max_evals, ftol, ubest, fbest, nevals)
        procedure(objective_fn) :: f             !! the objective
        real(wp), intent(in) :: u0(:)            !! starting point in the unit cube
        real(wp), intent(in) :: step             !! initial simplex step
        real(wp), intent(in) :: ftol             !! stop when the simplex's values agree within ftol
        integer, intent(in) :: max_evals         !! most evaluations
        real(wp), intent(out) :: ubest(size(u0)) !! best point
        real(wp), intent(out) :: fbest           !! objective there
        integer, intent(out) :: nevals           !! evaluations made
        real(wp) :: x(size(u0), size(u0) + 1), fx(size(u0) + 1), xc(size(u0)), xr(size(u0)), xe(size(u0))
        real(wp) :: xk(size(u0)), fr, fe, fk
        integer :: n, i, order(size(u0) + 1)
        n = size(u0)
        x(:, 1) = u0
        do i = 1, n
            x(:, i + 1) = u0
            x(i, i + 1) = u0(i) + merge(step, -step, u0(i) + step <= one)
        end do
        nevals = 0
        do i = 1, n + 1
            fx(i) = feval(x(:, i))
        end do
        do while (nevals < max_evals)
            order = sort_index(fx)
            x = x(:, order); fx = fx(order)
            if (fx(n + 1) - fx(1) <= ftol) exit
            xc = sum(x(:, 1:n), dim=2)/n
            xr = clamp(xc + (xc - x(:, n + 1)))
            fr = feval(xr)
            if (fr < fx(1)) then
                xe = clamp(xc + 2*(xc - x(:, n + 1)))
                fe = feval(xe)
                if (fe < fr) then
                    x(:, n + 1) = xe; fx(n + 1) = fe
                else
                    x(:, n + 1) = xr; fx(n + 1) = fr
                end if
            else if (fr < fx(n)) then
                x(:, n + 1) = xr; fx(n + 1) = fr
            else
                if (fr < fx(n + 1)) then
                    xk = clamp(xc + 0.5_wp*(xr - xc))          ! outside contraction
                else
                    xk = clamp(xc + 0.5_wp*(x(:, n + 1) - xc)) ! inside contraction
                end if
                fk = feval(xk)
                if (fk < min(fr, fx(n + 1))) then
                    x(:, n + 1) = xk; fx(n + 1) = fk
                else
                    do i = 2, n + 1                            ! shrink towards the best
                        x(:, i) = x(:, 1) + 0.5_wp*(x(:, i) - x(:, 1))
                        fx(i) = feval(x(:, i))
                    end do
                end if
            end if
        end do
        i = minloc(fx, dim=1)
        ubest = x(:, i); fbest = fx(i)
    contains
        real(wp) function feval(u)
            real(wp), intent(in) :: u(:)
            feval = f(u)
            nevals = nevals + 1
        end function feval
    end subroutine nelder_mead

    !> Nelder-Mead from u0, then restarted with a fresh simplex (the same
    !! step) about its best point while a restart lowers the objective by
    !! more than ftol and evaluations for one more simplex are left: a
    !! simplex that has collapsed short of the minimum starts again.
    subroutine restarted_nelder_mead(f, u0, step, max_evals, ftol, ubest, fbest, nevals)
        procedure(objective_fn) :: f             !! the objective
        real(wp), intent(in) :: u0(:)            !! starting point in the unit cube
        real(wp), intent(in) :: step             !! initial simplex step of every run
        integer, intent(in) :: max_evals         !! most evaluations in all
        real(wp), intent(in) :: ftol             !! a run stops when its simplex's values agree within ftol
        real(wp), intent(out) :: ubest(size(u0)) !! best point
        real(wp), intent(out) :: fbest           !! objective there
        integer, intent(out) :: nevals           !! evaluations made
        real(wp) :: unew(size(u0)), fnew
        integer :: n
        logical :: gained
        call nelder_mead(f, u0, step, max_evals, ftol, ubest, fbest, nevals)
        do while (max_evals - nevals > 2*(size(u0) + 1))
            call nelder_mead(f, ubest, step, max_evals - nevals, ftol, unew, fnew, n)
            nevals = nevals + n
            gained = fbest - fnew > ftol
            if (fnew < fbest) then
                ubest = unew; fbest = fnew
            end if
            if (.not. gained) exit
        end do
    end subroutine restarted_nelder_mead

    pure function clamp(u) result(c)
        real(wp), intent(in) :: u(:)
        real(wp) :: c(size(u))
        c = min(one, max(zero, u))
    end function clamp

    !> Position of value x in the unit range of parameter p (inverse of spread_value).
    pure real(wp) function unit_of(p, x) result(u)
        type(sweep_param_t), intent(in) :: p
        real(wp), intent(in) :: x
        if (p%log_spacing) then
            u = (log(x) - log(p%low))/(log(p%high) - log(p%low))
        else
            u = (x - p%low)/(p%high - p%low)
        end if
        u = min(one, max(zero, u))
    end function unit_of

    !> Run the calibration: the LHS starting points, then Nelder-Mead from
    !! the best, restarted about its best point while a restart gains more
    !! than 1e-4 and evaluations are left; the history and the result on
    !! unit lu.
    subroutine calibrate(cal, lu, vbest, jbest, nevals)
        type(calibration_t), intent(in) :: cal   !! the calibration
        integer, intent(in) :: lu                    !! listing unit
        real(wp), intent(out) :: vbest(:)            !! fitted parameter values
        real(wp), intent(out) :: jbest               !! objective there
        integer, intent(out) :: nevals               !! model evaluations (each runs every case)
        real(wp), allocatable :: design(:, :)
        real(wp) :: u0(size(cal%sw(1)%params)), ubest(size(u0)), j, jstart, lmax, lp
        type(score_t) :: sc(size(cal%sw))
        logical :: ok
        integer :: r, k, nnm
        associate (par => cal%sw(1)%params)
            write (lu, '(a)') 'CALIBRATION: '//trim(cal%title)
            write (lu, '(a,i0,a,i0,a,i0)') 'cases ', size(cal%sw), ', parameters ', size(par), ', seed ', cal%seed
            write (lu, '(a,es10.3,a,es10.3,a,es10.3)') 'objective J = (1 - R) + W P + WT T; W ', cal%peak_weight, &
                ', WT ', cal%time_weight, ', PEAK MARGIN M ', cal%peak_margin
            if (cal%max_evals == 0) then                 ! score the decks as they are, or at VALUES
                vbest = par%nominal
                if (size(cal%values) == size(par)) vbest = cal%values
                call evaluate(cal, vbest, jbest, sc, ok, lmax, lp)
                nevals = 1
                call score_report(cal, sc, jbest, lu)
                call rest_report(lmax, lp)
                return
            end if
            design = sweep_design(cal%sw(1))
            jstart = huge(one)
            nevals = 0
            do r = 1, size(design, 2)
                call evaluate(cal, design(:, r), j, sc, ok)
                nevals = nevals + 1
                call report('start', nevals, j, design(:, r))
                if (j < jstart) then
                    jstart = j
                    u0 = [(unit_of(par(k), design(k, r)), k=1, size(par))]
                end if
            end do
            call restarted_nelder_mead(obj, u0, 0.15_wp, max(cal%max_evals - nevals, size(par) + 2), 1.0e-4_wp, &
                                       ubest, jbest, nnm)
            vbest = values_of(ubest)
            write (lu, '(a,f9.5,a,i0,a)') 'BEST OBJECTIVE ', jbest, ' AFTER ', nevals, ' EVALUATIONS'
            call evaluate(cal, vbest, j, sc, ok, lmax, lp)
            call score_report(cal, sc, j, lu)
            call rest_report(lmax, lp)
            do k = 1, size(par)
                write (lu, '(a,a10,a,a10,a,es12.5,a,es12.5,a)') 'PARAM ', par(k)%name, ' = ', field_text(vbest(k)), &
                    '   (bounds ', par(k)%low, ' to ', par(k)%high, ')'
            end do
        end associate
    contains
        function obj(u) result(f)
            real(wp), intent(in) :: u(:)
            real(wp) :: f
            real(wp) :: v(size(u))
            type(score_t) :: s(size(cal%sw))
            logical :: good
            v = values_of(u)
            call evaluate(cal, v, f, s, good)
            nevals = nevals + 1
            call report('nelder', nevals, f, v)
        end function obj

        function values_of(u) result(v)
            real(wp), intent(in) :: u(:)
            real(wp) :: v(size(u))
            character(len=10) :: txt
            integer :: i
            do i = 1, size(u)
                v(i) = spread_value(cal%sw(1)%params(i), u(i))
                txt = field_text(v(i))
                if (cal%sw(1)%params(i)%kind == par_field) read (txt, *) v(i)
            end do
        end function values_of

        subroutine rest_report(lmax, lp)
            real(wp), intent(in) :: lmax, lp
            write (lu, '(a,es10.3,a)') 'LARGEST REAL PART AT REST ', lmax, ' 1/S'
            if (cal%passive .and. lp < huge(one)) &
                write (lu, '(a,es10.3,a)') 'LARGEST REAL PART AT REST WITHOUT MUSCLES ', lp, ' 1/S'
        end subroutine rest_report

        subroutine report(stage, n, f, v)
            character(len=*), intent(in) :: stage
            integer, intent(in) :: n
            real(wp), intent(in) :: f, v(:)
            integer :: i
            write (lu, '(a8,i6,f10.5,*(1x,a10))') stage, n, f, (field_text(v(i)), i=1, size(v))
            flush (lu)
        end subroutine report
    end subroutine calibrate

    !> The ratings and peaks of every case, three significant digits.
    subroutine score_report(cal, sc, j, lu)
        type(calibration_t), intent(in) :: cal
        type(score_t), intent(in) :: sc(:)
        real(wp), intent(in) :: j
        integer, intent(in) :: lu
        integer :: c, k
        write (lu, '(a,f8.4)') 'OBJECTIVE J = ', j
        do c = 1, size(sc)
            write (lu, '(a,a,a,f7.4)') 'CASE ', trim(cal%decks(c)), ': MEAN RATING ', sum(sc(c)%rating)/nrated
            do k = 1, nrated
                write (lu, '(2x,a10,a,f6.3,a,f6.3,a,f6.3)') rated_channels(k), ' RATING ', sc(c)%rating(k), &
                    '  C ', sc(c)%corridor(k), '  X ', sc(c)%xcorr(k)
            end do
            do k = 1, npeaks
                write (lu, '(2x,a16,a,es10.3,a,f6.1,a,es10.3,a,es9.2,a,f6.1,a,f5.1,a,f6.2)') peak_names(k), &
                    ' MODEL ', sc(c)%peak(k), ' AT ', sc(c)%time(k), ' MS; VOLUNTEERS ', cal%vol(c)%peak_mean(k), &
                    ' +- ', cal%vol(c)%peak_sd(k), ' AT ', cal%vol(c)%time_mean(k), ' +- ', cal%vol(c)%time_sd(k), &
                    '; Z ', sc(c)%z(k)
            end do
        end do
    end subroutine score_report

end module hn_calibrate
