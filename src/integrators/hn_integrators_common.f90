!> Helpers shared by the methods of hn_integrators: landing on tstop,
!! accepting a step, the error norm and the step-too-small message.
submodule(hn_integrators) hn_integrators_common
    implicit none

contains

    module procedure clip_step
        hc = h
        if (t + stretch*h >= tstop) hc = tstop - t
    end procedure clip_step

    module procedure accept
        me%told = me%t
        me%yold = me%y
        me%fold = me%f
        me%t = tnew
        me%y = ynew
        me%f = fnew
        me%nsteps = me%nsteps + 1
    end procedure accept

    module procedure err_norm
        r = sqrt(sum((e/(me%atol + me%rtol*max(abs(y0), abs(y1))))**2)/size(e))
    end procedure err_norm

    module procedure at_current_point
        done = me%t - me%told <= zero .or. tout >= me%t
        if (.not. done) return
        yout = me%y
        if (present(dydt)) dydt = me%f
    end procedure at_current_point

    module procedure step_too_small
        stat = stat_step_failed
        write (errmsg, '(a,es10.3,a,es12.5,a)') 'the step fell below ', hmin, ' s at t = ', t, &
            ' s: the method cannot meet the tolerance there'
    end procedure step_too_small

end submodule hn_integrators_common
