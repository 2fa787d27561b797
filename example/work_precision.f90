!> Work-precision benchmark (not a test): for the NBDL 15 g sled, the
!! forehead impact 6-2 and a stiffened variant of 6-2 (every element
!! stiffness x100, first 30 ms), every integrator over a sweep of steps or
!! tolerances: error against a converged reference -- the largest
!! difference in head rotation HEAD_THETY [deg] and head angular velocity
!! HEAD_OMEGY [rad/s] over the samples of the run -- against wall time and
!! dynamics evaluations. Writes a table on stdout and the rows as CSV.
!!
!!   fpm run --example work_precision --profile release -- docs/work_precision.csv
!!   hhneck-plot-work-precision docs/work_precision.csv docs/work_precision.png
program work_precision
    use hn_kinds, only: wp
    use hn_case, only: case_t
    use bench_decks, only: read_stiffened_case
    use hn_run, only: run_state_t, run_result_t
    use hn_channels, only: channel_set_t, channels_define
    implicit none

    type :: config_t
        character(len=8) :: method
        real(wp) :: h, rtol
    end type config_t

    character(len=256) :: csvname
    integer :: csv
    real(wp) :: best_wall, best_rtf
    character(len=80) :: best

    csvname = 'work_precision.csv'
    if (command_argument_count() >= 1) call get_command_argument(1, csvname)
    open (newunit=csv, file=trim(csvname), status='replace', action='write')
    write (csv, '(a)') 'case,method,step,rtol,err_theta_deg,err_omega_rad_s,wall_s,evals,steps,status'
    write (*, '(a)') 'case        method    step      rtol   err theta  err omega   wall (s)    evals   steps  status'

    call sweep('nbdl15g', 'input/nbdl15g.inp', 0.25_wp, .false.)
    call sweep('case6-2', 'input/case6-2.inp', 0.1_wp, .false.)
    call sweep('stiff6-2', 'input/case6-2.inp', 0.03_wp, .true.)
    close (csv)

contains

    subroutine sweep(label, deck, t_end, stiffen)
        character(len=*), intent(in) :: label, deck
        real(wp), intent(in) :: t_end
        logical, intent(in) :: stiffen
        type(config_t), allocatable :: configs(:)
        real(wp), allocatable :: th_ref(:), om_ref(:), th_alt(:), om_alt(:)
        type(run_result_t) :: res
        real(wp) :: eth, eom, hs
        integer :: k, ith, iom
        character(len=16) :: status

        hs = merge(0.05_wp, 1.0_wp, stiffen)
        configs = [ &
                  (config_t('RK4', 4.0e-4_wp*hs/2**k, 0.0_wp), k=0, 5), &
                  (config_t('ABM4', 4.0e-4_wp*hs/2**k, 0.0_wp), k=0, 5), &
                  (config_t('DOPRI5', 1.0e-4_wp, 10.0_wp**(-k)), k=3, 9), &
                  (config_t('ADAMS', 1.0e-4_wp, 10.0_wp**(-k)), k=3, 9), &
                  (config_t('ROS2', 1.0e-4_wp, 10.0_wp**(-k)), k=2, 5), &
                  (config_t('ROS34PW2', 1.0e-4_wp, 10.0_wp**(-k)), k=2, 6)]

        call one_run(deck, t_end, stiffen, config_t('DOPRI5', 1.0e-5_wp, 1.0e-11_wp), res, ith, iom)
        th_ref = res%samples(ith, :)
        om_ref = res%samples(iom, :)
        call one_run(deck, t_end, stiffen, config_t('ADAMS', 1.0e-5_wp, 1.0e-11_wp), res, ith, iom)
        th_alt = res%samples(ith, :)
        om_alt = res%samples(iom, :)
        write (*, '(a,a,es9.2,a,es9.2,a)') trim(label), ': reference DOPRI5 rtol 1e-11; ADAMS at 1e-11 differs by ', &
            maxval(abs(th_alt - th_ref)), ' deg, ', maxval(abs(om_alt - om_ref)), ' rad/s'
        best_wall = huge(1.0_wp)
        best = ''
        do k = 1, size(configs)
            call one_run(deck, t_end, stiffen, configs(k), res, ith, iom)
            if (res%exit_code == 0) then
                eth = maxval(abs(res%samples(ith, :) - th_ref))
                eom = maxval(abs(res%samples(iom, :) - om_ref))
                status = 'ok'
                if (label == 'nbdl15g' .and. eth <= 0.1_wp .and. res%wall < best_wall) then
                    best_wall = res%wall
                    best_rtf = t_end/res%wall
                    write (best, '(a,a,es9.2,a,es9.2)') trim(configs(k)%method), ' step ', configs(k)%h, &
                        ' rtol ', configs(k)%rtol
                end if
            else
                eth = -1; eom = -1
                status = 'stopped'
            end if
            write (*, '(a10,2x,a8,es9.2,es9.1,2es11.3,f11.3,i9,i8,2x,a)') label, configs(k)%method, configs(k)%h, &
                configs(k)%rtol, eth, eom, res%wall, res%nevals, res%nsteps, trim(status)
            write (csv, '(a,",",a,",",es10.3,",",es10.3,",",es11.4,",",es11.4,",",es11.4,",",i0,",",i0,",",a)') &
                label, trim(configs(k)%method), configs(k)%h, configs(k)%rtol, eth, eom, res%wall, res%nevals, &
                res%nsteps, trim(status)
            flush (csv)
        end do
        if (label == 'nbdl15g') write (*, '(a,a,a,f8.3,a,f7.3,a)') 'NBDL 15 g, head rotation within 0.1 deg: fastest ', &
            trim(best), ': wall ', best_wall, ' s, real-time factor ', best_rtf, ' (simulated / wall)'
    end subroutine sweep

        !> One run of `deck` to t_end with configuration cfg, samples kept.
        subroutine one_run(deck, t_end, stiffen, cfg, r, i_th, i_om)
            character(len=*), intent(in) :: deck
            real(wp), intent(in) :: t_end
            logical, intent(in) :: stiffen
            type(config_t), intent(in) :: cfg
            type(run_result_t), intent(out) :: r
            integer, intent(out) :: i_th, i_om
            type(case_t) :: cs
            type(channel_set_t) :: ch
            integer :: lu
            character(len=*), parameter :: tmp = 'work_precision_deck.inp'
            call read_stiffened_case(deck, tmp, merge(100.0_wp, 0.0_wp, stiffen), cs)
            cs%integrator = cfg%method
            cs%h = cfg%h
            cs%rtol = cfg%rtol
            cs%atol = cfg%rtol*1.0e-2_wp
            cs%t_end = t_end
            cs%print_dt = t_end/10
            call channels_define(cs, ch)
            i_th = findloc(ch%name, 'HEAD_THETY', dim=1)
            i_om = findloc(ch%name, 'HEAD_OMEGY', dim=1)
            open (newunit=lu, file='/dev/null', action='write')
            block
                type(run_state_t) :: run
                call run%execute(cs, lu, '', r, keep_samples=.true.)
            end block
            close (lu)
        end subroutine one_run

end program work_precision
