!> The HDF5 result file of a run: the deck, model tables, every channel at
!! the sampling interval, body positions and orientations, coordinates, the
!! injury criteria and the run status, with units on every dataset. Layout
!! in docs/output-format.md.
!!
!! Samples are buffered and written a block (one chunk of every series) at a
!! time; the file is flushed to disk when a block is written and at most
!! every few seconds of wall time at the print times, so a run killed
!! outright loses little, and a run stopped with a message keeps everything.
!! The file says `status = incomplete` from the moment it is created until
!! the run closes it; a write failure (a full disk) stops the writing and
!! the partial file is removed with a message (hn_h5).
module hn_results
    use hn_kinds, only: wp, zero, msglen, i8
    use hn_status, only: stat_ok
    use hn_case, only: case_t
    use hn_channels, only: channel_set_t
    use hn_dynamics, only: dyn_workspace_t
    use hn_tree, only: dof_label
    use hn_h5, only: h5_file_t
    use hn_h5_read, only: h5_read_string_attr
    use hn_dump, only: dump_open
    use hn_assessment, only: assessment_t
    use hn_injury, only: occupants
    use hn_posix, only: file_kind, kind_regular
    use hn_results_model, only: write_element_tables
    implicit none
    private

    public :: results_t, results_replaceable

    integer, parameter :: block = 1024              !! samples per written block (and chunk)
    !> Version of the file's layout (root attribute schema_version; the
    !! rules for changing it in docs/output-format.md).
    integer, parameter, public :: results_schema_version = 2
    real(wp), parameter :: flush_wall = 2.0_wp      !! at most this long between flushes at print times [s]

    !> Result file and its sample buffers.
    type :: results_t
        type(h5_file_t) :: h5
        logical :: active = .false.
        integer :: nbuf = 0, nwritten = 0
        real(wp) :: t_last = zero                   !! time of the last sample taken
        integer(i8) :: flushed_at = 0               !! clock count of the last flush
        real(wp), allocatable :: time(:), chan(:, :), pos(:, :, :), rot(:, :, :, :), x(:, :), xd(:, :)
    contains
        procedure :: open => results_open
        procedure :: sample => results_sample
        procedure :: flush => results_flush
        procedure :: close => results_close
        procedure :: criteria => results_criteria
        procedure :: counts => results_counts
        procedure :: failed => results_failed
        procedure :: error => results_error
    end type results_t

contains

    !> Whether a run of case `cs` may write `fname` (before it starts): yes
    !! when there is no such file, or when the file was written by the same
    !! deck, the same title (root attribute `title`) from the same deck file
    !! (`deck_file`, a name without directories; a deck read from standard
    !! input matches any). Otherwise `errmsg` names the file, the deck that
    !! wrote it and this run's deck, and what to do (--overwrite, --h5).
    subroutine results_replaceable(fname, cs, ok, errmsg)
        character(len=*), intent(in) :: fname            !! the result file the run would write
        type(case_t), intent(in) :: cs                   !! the run's case (title, deck file)
        logical, intent(out) :: ok                       !! the run may write it
        character(len=msglen), intent(out) :: errmsg     !! why not ('' when ok)
        character(len=200) :: title, file
        character(len=:), allocatable :: mine
        integer :: st, st2
        ok = .true.
        errmsg = ''
        if (file_kind(fname) /= kind_regular) return
        call h5_read_string_attr(fname, '/', 'title', title, st)
        call h5_read_string_attr(fname, '/', 'deck_file', file, st2)
        if (st2 /= 0) file = ''
        mine = trim(deck_file_name(cs))
        if (st == 0) then
            ok = trim(title) == trim(cs%model%title)
            if (ok .and. len_trim(file) > 0 .and. file /= 'stdin' .and. mine /= 'stdin') ok = trim(file) == mine
        else
            ok = .false.
        end if
        if (ok) return
        if (st == 0) then
            errmsg = 'the result file '//trim(fname)//' holds the results of another deck ("'//trim(title)//'"'
            if (len_trim(file) > 0) errmsg = trim(errmsg)//', '//trim(file)
            errmsg = trim(errmsg)//'), not of this one ("'//trim(cs%model%title)//'", '//mine//')'
        else
            errmsg = 'the file '//trim(fname)//' is not a result file of hhneck (it has no title)'
        end if
        errmsg = trim(errmsg)//'; nothing was run and the file is kept: give --overwrite to replace it, or '// &
                 '--h5 FILE to write another file'
    end subroutine results_replaceable

    !> The deck file a case was read from, as the result file records it.
    pure function deck_file_name(cs) result(s)
        type(case_t), intent(in) :: cs   !! the case (deck_file: '' when not set)
        character(len=len(cs%deck_file)) :: s
        s = cs%deck_file
        if (len_trim(s) == 0) s = 'stdin'
    end function deck_file_name

    !> Create the file and write the deck and model tables. `note` says what
    !! was done to files already there (an older result removed, a missing
    !! directory created).
    subroutine results_open(me, cs, ch, fname, code_version, stat, errmsg, note)
        class(results_t), intent(inout) :: me
        type(case_t), intent(in) :: cs                        !! the case (deck, model, times)
        type(channel_set_t), intent(in) :: ch                 !! channel names and units
        character(len=*), intent(in) :: fname                 !! result file name (.h5)
        character(len=*), intent(in) :: code_version          !! program version written to the file
        integer, intent(out) :: stat                          !! stat_ok or stat_io
        character(len=msglen), intent(out) :: errmsg          !! the reason on failure
        character(len=msglen), intent(out), optional :: note  !! what was done to files already there
        integer :: nb, n, k, nexp
        integer(i8) :: rate
        call me%h5%create(fname, stat, errmsg)
        if (present(note)) note = me%h5%note
        if (stat /= 0) return
        me%active = .true.
        nb = cs%model%tree%nbody
        n = cs%model%tree%ndof
        associate (h => me%h5)
            call h%attr_string('/', 'code', 'HHNECK '//code_version)
            call h%attr_int('/', 'schema_version', results_schema_version)
            call h%attr_string('/', 'title', trim(cs%model%title))
            call h%attr_string('/', 'deck_file', trim(deck_file_name(cs)))
            call h%attr_string('/', 'status', 'incomplete')
            call h%attr_string('/', 'message', 'the run has not closed this file: it is running, or was killed')
            call write_deck(h, cs)
            call write_model(h, cs)
            call h%group('/channels')
            call h%attr_strings('/channels', 'names', ch%name(1:ch%n))
            call h%attr_strings('/channels', 'units', ch%units(1:ch%n))
            call h%attr_string('/channels', 'description', 'one dataset per channel; attributes names and '// &
                               'units list them in the order of the listing')
            nexp = max(1, min(block, nint((cs%t_end - cs%t_start)/cs%sample_dt) + 1))
            do k = 1, ch%n
                call h%series('/channels/'//trim(ch%name(k)), [integer ::], nexp)
                call h%attr_string('/channels/'//trim(ch%name(k)), 'units', trim(ch%units(k)))
            end do
            call h%series('/time', [integer ::], nexp)
            call h%attr_string('/time', 'units', 's')
            call h%group('/bodies')
            call h%series('/bodies/position', [3, nb], nexp)
            call h%attr_string('/bodies/position', 'units', 'm')
            call h%attr_string('/bodies/position', 'description', 'mass-centre position of each body in R; '// &
                               'h5py shape (time, body, xyz)')
            call h%series('/bodies/rotation', [3, 3, nb], nexp)
            call h%attr_string('/bodies/rotation', 'units', '1')
            call h%attr_string('/bodies/rotation', 'description', 'body-to-R rotation matrix S of each body; '// &
                               'h5py [t, k, j, i] is S_ij of body k')
            call h%group('/coordinates')
            call h%series('/coordinates/x', [n], nexp)
            call h%attr_string('/coordinates/x', 'units', 'm for translations (tx, ty, tz), rad for rotations '// &
                               '(rx, ry, rz); per column in column_units')
            call h%attr_strings('/coordinates/x', 'column_units', coord_units(cs, ''))
            call h%attr_strings('/coordinates/x', 'columns', coord_labels(cs))
            call h%series('/coordinates/xd', [n], nexp)
            call h%attr_string('/coordinates/xd', 'units', 'm/s for translations, rad/s for rotations; '// &
                               'per column in column_units')
            call h%attr_strings('/coordinates/xd', 'column_units', coord_units(cs, '/s'))
            call h%attr_strings('/coordinates/xd', 'columns', coord_labels(cs))
            if (size(cs%dump_times) > 0) call dump_open(h, cs%model, size(cs%dump_times))
            call h%flush()
            stat = h%stat
            errmsg = h%errmsg
            ! a file that could not be set up is removed with its lock (the message says so)
            if (stat /= stat_ok) call h%close(.false., stat, errmsg)
        end associate
        if (stat /= stat_ok) then
            me%active = .false.
            return
        end if
        allocate (me%time(block), me%chan(block, ch%n), me%pos(3, nb, block), me%rot(3, 3, nb, block))
        allocate (me%x(n, block), me%xd(n, block))
        me%nbuf = 0
        call system_clock(me%flushed_at, rate)
    end subroutine results_open

    !> The deck as read: /deck/text (one 80-column card image per element),
    !! /deck/source and /deck/line (where each came from).
    subroutine write_deck(h, cs)
        type(h5_file_t), intent(inout) :: h
        type(case_t), intent(in) :: cs
        character(len=80), allocatable :: text(:)
        character(len=:), allocatable :: sources(:)
        integer, allocatable :: lines(:)
        integer :: k, n, lmax
        n = size(cs%deck)
        lmax = 1
        do k = 1, n
            lmax = max(lmax, len(cs%deck(k)%source))
        end do
        allocate (text(n), lines(n))
        allocate (character(len=lmax) :: sources(n))
        do k = 1, n
            text(k) = cs%deck(k)%text
            sources(k) = cs%deck(k)%source
            lines(k) = cs%deck(k)%line
        end do
        call h%group('/deck')
        call h%attr_string('/deck', 'description', 'the card images as read (comments omitted, INCLUDE files '// &
                           'expanded), where each came from, and its line there')
        call h%write_strings('/deck/text', text)
        call h%write_strings('/deck/source', sources)
        call h%write_int('/deck/line', lines, [n])
        call h%attr_string('/deck/line', 'units', '1')
        if (allocated(cs%subtitles)) then
            if (size(cs%subtitles) > 0) then
                call h%write_strings('/deck/subtitles', cs%subtitles)
                call h%attr_string('/deck/subtitles', 'description', 'the titles of the INCLUDEd case decks, '// &
                                   'in deck order (the root attribute title is the deck''s own)')
            end if
        end if
        if (allocated(cs%changes)) then
            if (size(cs%changes) > 0) then
                call h%write_strings('/deck/changes', cs%changes)
                call h%attr_string('/deck/changes', 'description', 'what the CHANGE cards changed for this run '// &
                                   '(old and new values, the card)')
            end if
        end if
    end subroutine write_deck

    !> /model: names, tree and inertia tables, with units.
    subroutine write_model(h, cs)
        type(h5_file_t), intent(inout) :: h
        type(case_t), intent(in) :: cs
        integer :: nb, n
        nb = cs%model%tree%nbody
        n = cs%model%tree%ndof
        call h%group('/model')
        call h%attr_strings('/model', 'bodies', cs%model%tree%name(1:nb))
        call h%attr_strings('/model', 'coordinates', coord_labels(cs))
        call h%write_int('/model/parent', cs%model%tree%parent, [nb])
        call h%attr_string('/model/parent', 'units', '1')
        call h%attr_string('/model/parent', 'description', 'parent body number, 1-based (0 = the inertial frame R)')
        call h%write_real('/model/mass', cs%model%tree%mass, [nb])
        call h%attr_string('/model/mass', 'units', 'kg')
        call h%write_real('/model/inertia', cs%model%tree%inertia, [3, 3, nb])
        call h%attr_string('/model/inertia', 'units', 'kg m^2')
        call h%attr_string('/model/inertia', 'description', 'centroidal inertia matrix in body axes')
        call h%write_real('/model/joint_in_parent', cs%model%tree%joint_parent, [3, nb])
        call h%attr_string('/model/joint_in_parent', 'units', 'm')
        call h%attr_string('/model/joint_in_parent', 'description', 'joint point in the parent frame, from '// &
                           'the parent''s mass centre (root: a point of R)')
        call h%write_real('/model/joint_in_body', cs%model%tree%joint_child, [3, nb])
        call h%attr_string('/model/joint_in_body', 'units', 'm')
        call h%attr_string('/model/joint_in_body', 'description', 'the joint point in the body frame, from '// &
                           'its own mass centre')
        call h%write_int('/model/prescribed', merge(1, 0, cs%model%prescribed), [n])
        call h%attr_string('/model/prescribed', 'units', '1')
        call h%attr_string('/model/prescribed', 'description', '1 where the coordinate is prescribed, 0 where free')
        call write_element_tables(h, cs%model)
    end subroutine write_model

    !> Labels of the active coordinates, e.g. ["T1.tx", "T1.ty", ...].
    function coord_labels(cs) result(s)
        type(case_t), intent(in) :: cs
        character(len=32) :: s(cs%model%tree%ndof)
        integer :: j
        do j = 1, cs%model%tree%ndof
            s(j) = dof_label(cs%model%tree, j)
        end do
    end function coord_labels

    !> Unit of each active coordinate ("m" or "rad", then `suffix`).
    function coord_units(cs, suffix) result(s)
        type(case_t), intent(in) :: cs
        character(len=*), intent(in) :: suffix
        character(len=8) :: s(cs%model%tree%ndof)
        integer :: j
        do j = 1, cs%model%tree%ndof
            if (cs%model%tree%dof_local(j) <= 3) then
                s(j) = 'm'//suffix
            else
                s(j) = 'rad'//suffix
            end if
        end do
    end function coord_units

    !> Buffer one sample; writes a block when the buffer is full.
    subroutine results_sample(me, t, ch, ws)
        class(results_t), intent(inout) :: me
        real(wp), intent(in) :: t                    !! sample time [s]
        type(channel_set_t), intent(in) :: ch        !! channel values at t
        type(dyn_workspace_t), intent(in) :: ws      !! kinematics and coordinates at t
        if (.not. me%active) return
        me%nbuf = me%nbuf + 1
        me%time(me%nbuf) = t
        me%chan(me%nbuf, :) = ch%value
        me%pos(:, :, me%nbuf) = ws%kin%r
        me%rot(:, :, :, me%nbuf) = ws%kin%s
        me%x(:, me%nbuf) = ws%x
        me%xd(:, me%nbuf) = ws%xd
        me%t_last = t
        if (me%nbuf == block) call write_block(me, ch, .true.)
    end subroutine results_sample

    !> At a print time: write the buffered samples and flush the file when
    !! the last flush is more than a few seconds of wall time ago.
    subroutine results_flush(me, ch)
        class(results_t), intent(inout) :: me
        type(channel_set_t), intent(in) :: ch        !! channel names
        integer(i8) :: now, rate
        if (.not. me%active) return
        call system_clock(now, rate)
        if (real(now - me%flushed_at, wp) < flush_wall*real(rate, wp)) return
        call write_block(me, ch, .true.)
    end subroutine results_flush

    !> Write the buffered samples (and flush the file to disk).
    subroutine write_block(me, ch, to_disk)
        class(results_t), intent(inout) :: me
        type(channel_set_t), intent(in) :: ch
        logical, intent(in) :: to_disk
        integer :: k, nb
        integer(i8) :: rate
        nb = me%nbuf
        if (nb > 0) then
            call me%h5%append('/time', me%time, nb)
            do k = 1, ch%n
                call me%h5%append('/channels/'//trim(ch%name(k)), me%chan(1:nb, k), nb)
            end do
            call me%h5%append('/bodies/position', me%pos(:, :, 1:nb), nb)
            call me%h5%append('/bodies/rotation', me%rot(:, :, :, 1:nb), nb)
            call me%h5%append('/coordinates/x', me%x(:, 1:nb), nb)
            call me%h5%append('/coordinates/xd', me%xd(:, 1:nb), nb)
            me%nwritten = me%nwritten + nb
            me%nbuf = 0
        end if
        if (to_disk) then
            call me%h5%flush()
            call system_clock(me%flushed_at, rate)
        end if
    end subroutine write_block

    !> True once a write has failed (the run should stop: exit 4).
    logical function results_failed(me)
        class(results_t), intent(in) :: me
        results_failed = me%active .and. me%h5%failed()
    end function results_failed

    !> The message of the first write failure.
    function results_error(me) result(s)
        class(results_t), intent(in) :: me
        character(len=:), allocatable :: s
        s = trim(me%h5%errmsg)
    end function results_error

    !> Write what is left, the status ('complete' or 'incomplete') and
    !! message, close, and give the file its final name. `note` says where
    !! the results are when the run is incomplete, or that the partial file
    !! was removed after a write failure ('' when there is nothing to say).
    subroutine results_close(me, ch, status, message, stat, errmsg, note)
        class(results_t), intent(inout) :: me
        type(channel_set_t), intent(in) :: ch                 !! channel names
        character(len=*), intent(in) :: status                !! 'complete' or 'incomplete'
        character(len=*), intent(in) :: message               !! why the run stopped
        integer, intent(out) :: stat                          !! stat_ok or stat_io
        character(len=msglen), intent(out) :: errmsg          !! the reason on failure
        character(len=msglen), intent(out), optional :: note  !! where the results are
        character(len=40) :: tt
        stat = 0; errmsg = ''
        if (present(note)) note = ''
        if (.not. me%active) return
        call write_block(me, ch, .false.)
        call me%h5%attr_string('/', 'status', status)
        call me%h5%attr_string('/', 'message', message)
        call me%h5%close(.true., stat, errmsg)
        me%active = .false.
        if (.not. present(note)) return
        if (stat == stat_ok .and. status /= 'complete' .and. file_kind(me%h5%final_name) == kind_regular) then
            write (tt, '(f12.5)') me%t_last
            write (note, '(5a,i0,a)') 'results up to t = ', trim(adjustl(tt)), ' s kept in ', me%h5%final_name, &
                ' (marked incomplete, ', me%nwritten, trim(merge(' sample) ', ' samples)', me%nwritten == 1))
        end if
    end subroutine results_close

    !> The integrator's counts as root attributes (docs/output-format.md):
    !! steps, rejected steps, dynamics evaluations (of the integration and
    !! at output times), Jacobians and factorizations of the iteration matrix.
    subroutine results_counts(me, steps, rejected, evaluations, output_evaluations, jacobians, factorizations)
        class(results_t), intent(inout) :: me
        integer, intent(in) :: steps                !! accepted steps
        integer, intent(in) :: rejected             !! rejected steps
        integer, intent(in) :: evaluations          !! dynamics evaluations of the integration
        integer, intent(in) :: output_evaluations   !! evaluations at output times
        integer, intent(in) :: jacobians            !! Jacobians formed (0: explicit methods)
        integer, intent(in) :: factorizations       !! factorizations of the iteration matrix
        if (.not. me%active) return
        call me%h5%attr_int('/', 'steps', steps)
        call me%h5%attr_int('/', 'rejected_steps', rejected)
        call me%h5%attr_int('/', 'evaluations', evaluations)
        call me%h5%attr_int('/', 'output_evaluations', output_evaluations)
        call me%h5%attr_int('/', 'jacobians', jacobians)
        call me%h5%attr_int('/', 'factorizations', factorizations)
    end subroutine results_counts

    !> Group /injury: each criterion's value and where it occurs, labelled
    !! and with units (docs/output-format.md); the filtered time histories
    !! (same time base as /time) as datasets.
    subroutine results_criteria(me, a)
        class(results_t), intent(inout) :: me
        type(assessment_t), intent(in) :: a      !! the run's injury assessment
        integer :: n
        real(wp), allocatable :: modes(:, :)
        if (.not. me%active) return
        associate (h => me%h5)
            call h%group('/injury')
            if (.not. a%computed) then
                call h%attr_string('/injury', 'note', trim(a%note))
                return
            end if
            call h%attr_string('/injury', 'description', 'injury criteria of the head and upper neck; each '// &
                               'group holds a value and where or when it occurs; histories share /time')
            call h%attr_string('/injury', 'reference_values', 'the reference_value attributes are injury '// &
                               'assessment reference values of crash-test dummies in standards, not limits of '// &
                               'this human model')
            associate (occ => occupants(a%occupant))
                call h%attr_string('/injury', 'occupant', trim(occ%code))
                call h%attr_string('/injury', 'occupant_label', trim(occ%label))
                call h%attr_string('/injury', 'occupant_source', trim(occ%source))
                call h%attr_string('/injury', 'occupant_verified', trim(merge('yes', 'no ', occ%verified)))
                call window(h, 'hic15', 'HIC over the worst window of at most 15 ms, head resultant acceleration '// &
                            'CFC 1000', a%hic15, a%hic15_t1, a%hic15_t2)
                call label(h, 'hic15', '49 CFR 571.208 S6.2 (FMVSS 208)', 'head mass-centre resultant '// &
                           'acceleration, CFC 1000; any impact direction', [700.0_wp], '1')
                call window(h, 'hic36', 'HIC over the worst window of at most 36 ms', a%hic36, a%hic36_t1, &
                            a%hic36_t2)
                call label(h, 'hic36', '49 CFR 571.208 S6.2 (FMVSS 208)', 'head mass-centre resultant '// &
                           'acceleration, CFC 1000; any impact direction', [1000.0_wp], '1')
                call h%group('/injury/nij')
                call label(h, 'nij', trim(occ%source), 'upper neck (occipital condyle), CFC 600; '// &
                           'intercepts of the '//trim(occ%label), [1.0_wp], '1')
                call h%write_real('/injury/nij/intercepts', [occ%crit%fz_tension, occ%crit%fz_compression, &
                                  occ%crit%my_flexion, occ%crit%my_extension], [4])
                call h%attr_string('/injury/nij/intercepts', 'units', 'N, N, N m, N m')
                call h%attr_string('/injury/nij/intercepts', 'description', 'Fzc tension, Fzc compression, '// &
                                   'Myc flexion, Myc extension ('//trim(occ%source)//')')
            end associate
            call scalar(h, '/injury/nij/value', a%nij_max, '1', 'peak Nij in each mode, in the order of modes')
            call scalar(h, '/injury/nij/time', a%nij_time, 's', 'time of each peak')
            call h%attr_strings('/injury/nij', 'modes', [character(len=3) :: 'NTE', 'NTF', 'NCE', 'NCF'])
            call h%attr_string('/injury/nij', 'description', 'Nij at the occipital condyle (CFC 600): tension-'// &
                               'extension, tension-flexion, compression-extension, compression-flexion')
            call peak(h, 'nic', 'peak NIC (T1 and head x-accelerations, CFC 60)', a%nic_max, a%nic_time, 'm^2/s^2')
            call label(h, 'nic', 'Bostrom et al. 1996', 'rear impact only (not a criterion for frontal or '// &
                       'lateral loading); x-accelerations CFC 60 along '// &
                       trim(merge('the head''s x axis  ', 'the inertial x axis', a%nic_frame == 'HEAD')), [15.0_wp], 'm^2/s^2')
            call h%attr_string('/injury/nic', 'frame', trim(a%nic_frame))
            call peak(h, 'tension', 'highest OC_FZ (tension positive), CFC 600', a%tension, a%tension_t, 'N')
            call peak(h, 'compression', 'lowest OC_FZ (compression negative), CFC 600', a%compression, &
                      a%compression_t, 'N')
            associate (occ => occupants(a%occupant))
                call label(h, 'tension', trim(occ%source), 'upper neck, CFC 600; '//trim(occ%label), &
                           [occ%tension], 'N')
                call label(h, 'compression', trim(occ%source), 'upper neck, CFC 600; '//trim(occ%label), &
                           [-occ%compression], 'N')
            end associate
            call peak(h, 'shear', 'highest |OC_FX|, CFC 600', a%shear, a%shear_t, 'N')
            call peak(h, 'flexion_moment', 'highest OC_MY (flexion positive), CFC 600', a%flexion, a%flexion_t, &
                      'N m')
            call peak(h, 'extension_moment', 'lowest OC_MY (extension negative), CFC 600', a%extension, &
                      a%extension_t, 'N m')
            call h%attr_string('/injury', 'direction', trim(a%direction))
            call h%attr_string('/injury', 'direction_rule', 'LATERAL if the largest |HT1_RX| exceeds the largest '// &
                               '|HT1_RY|; else REAR if the largest |HT1_RY| is an extension, FRONTAL if a flexion')
            call peak(h, 'lateral_moment', 'highest |OC_MX| (lateral bending moment at the occipital condyle), '// &
                      'CFC 600', a%lat_moment, a%lat_moment_t, 'N m')
            call frame(h, 'lateral_moment', 'head axes at the occipital condyle (OC_MX)', 'lateral')
            call peak(h, 'lateral_shear', 'highest |OC_FY| (lateral shear at the occipital condyle), CFC 600', &
                      a%lat_shear, a%lat_shear_t, 'N')
            call frame(h, 'lateral_shear', 'head axes at the occipital condyle (OC_FY)', 'lateral')
            call peak(h, 'lateral_bending', 'HT1_RX of the largest magnitude: the head''s lateral bending '// &
                      'relative to T1 (> 0 the top of the head to the right), unfiltered', a%lat_bend, &
                      a%lat_bend_t, 'deg')
            call frame(h, 'lateral_bending', 'T1 axes, Bryant x-y-z (HT1_RX)', 'lateral')
            call peak(h, 't1_ax', 'highest T1 x-acceleration, CFC 60, in NIC''s frame', a%t1_ax_max, &
                      a%t1_ax_max_t, 'g')
            call frame(h, 't1_ax', trim(a%nic_frame)//' (the frame of /injury/nic)', 'rear')
            call peak(h, 'head_ax', 'highest head x-acceleration, CFC 60, in NIC''s frame', a%head_ax_max, &
                      a%head_ax_max_t, 'g')
            call frame(h, 'head_ax', trim(a%nic_frame)//' (the frame of /injury/nic)', 'rear')
            call h%group('/injury/ndc')
            call h%attr_string('/injury/ndc', 'description', 'NDC points: the head relative to T1 where its '// &
                               'extension (lowest HT1_RY) and its retraction (lowest HT1_DX) peak; corridors not '// &
                               'sourced, not compared')
            call h%attr_string('/injury/ndc', 'source', 'Muser et al. 2000 (neck displacement criterion)')
            call frame(h, 'ndc', 'T1 axes: HT1_RY flexion positive, HT1_DX < 0 retraction', 'rear')
            call scalar(h, '/injury/ndc/extension', [a%ndc%ext_angle, a%ndc%ext_dx, a%ndc%ext_dz], &
                        'deg, mm, mm', 'angle, x, z at the extension peak')
            call scalar(h, '/injury/ndc/extension_time', [a%ndc%ext_time], 's', 'time of the extension peak')
            call scalar(h, '/injury/ndc/retraction', [a%ndc%ret_angle, a%ndc%ret_dx, a%ndc%ret_dz], &
                        'deg, mm, mm', 'angle, x, z at the retraction peak')
            call scalar(h, '/injury/ndc/retraction_time', [a%ndc%ret_time], 's', 'time of the retraction peak')
            call scalar(h, '/injury/ndc/flexion', [a%ndc%flex_angle, a%ndc%flex_dx], 'deg, mm', &
                        'angle, x at the flexion peak')
            call scalar(h, '/injury/ndc/flexion_time', [a%ndc%flex_time], 's', 'time of the flexion peak')
            call missing(h, 'nkm', 'Schmitt et al. 2002', 'not computed: the intercepts could not be checked '// &
                         'against a source')
            call missing(h, 'lnl', 'Heitplatz et al. 2003', 'not computed: the intercepts could not be checked '// &
                         'against a source')
            call missing(h, 'iv_nic', 'Panjabi et al. 1999', 'not computed: the joint rotations and ranges are '// &
                         'not passed to the assessment')
            n = size(a%head_ar)
            call h%group('/injury/history')
            call h%attr_string('/injury/history', 'description', 'filtered time histories at the times of /time')
            call series(h, 'head_ar_cfc1000', a%head_ar, [n], 'g', 'head resultant acceleration, CFC 1000')
            modes = transpose(a%nij_t)          ! (4, n): h5py reads (n, 4), time first
            call series(h, 'nij', modes, [4, n], '1', 'Nij modes NTE NTF NCE NCF; h5py shape (time, mode)')
            call series(h, 'nic', a%nic_t, [n], 'm^2/s^2', 'NIC')
            call series(h, 'oc_fx_cfc600', a%fx, [n], 'N', 'OC_FX, CFC 600')
            call series(h, 'oc_fz_cfc600', a%fz, [n], 'N', 'OC_FZ, CFC 600')
            call series(h, 'oc_my_cfc600', a%my, [n], 'N m', 'OC_MY, CFC 600')
            call series(h, 'oc_fy_cfc600', a%fy, [n], 'N', 'OC_FY, CFC 600')
            call series(h, 'oc_mx_cfc600', a%mx, [n], 'N m', 'OC_MX, CFC 600')
            call series(h, 'nic_head_ax_cfc60', a%nic_head, [n], 'm/s^2', 'head mass-centre x-acceleration '// &
                        'NIC is computed from, CFC 60, along the '// &
                        trim(merge('head''s x axis  ', 'inertial x axis', a%nic_frame == 'HEAD')))
            call series(h, 'nic_t1_ax_cfc60', a%nic_t1, [n], 'm/s^2', 'T1 mass-centre x-acceleration '// &
                        'NIC is computed from, CFC 60, along the '// &
                        trim(merge('head''s x axis  ', 'inertial x axis', a%nic_frame == 'HEAD')))
        end associate
    end subroutine results_criteria

    ! the writers of /injury's groups (results_criteria)
    subroutine scalar(h, path, v, units, description)
        type(h5_file_t), intent(inout) :: h
        character(len=*), intent(in) :: path, units, description
        real(wp), intent(in) :: v(:)
        if (size(v) == 1) then
            call h%write_real(path, v, [integer ::])
        else
            call h%write_real(path, v, [size(v)])
        end if
        call h%attr_string(path, 'units', units)
        call h%attr_string(path, 'description', description)
    end subroutine scalar
    subroutine label(h, name, source, applicability, ref, units)
        type(h5_file_t), intent(inout) :: h
        character(len=*), intent(in) :: name, source, applicability, units
        real(wp), intent(in) :: ref(:)
        call h%attr_string('/injury/'//name, 'source', source)
        call h%attr_string('/injury/'//name, 'applicability', applicability)
        call h%write_real('/injury/'//name//'/reference_value', ref, [integer ::])
        call h%attr_string('/injury/'//name//'/reference_value', 'units', units)
        call h%attr_string('/injury/'//name//'/reference_value', 'description', 'injury assessment '// &
                           'reference value of the dummy in the standard, not a limit of this model')
    end subroutine label
    subroutine window(h, name, description, v, t1, t2)
        type(h5_file_t), intent(inout) :: h
        character(len=*), intent(in) :: name, description
        real(wp), intent(in) :: v, t1, t2
        call h%group('/injury/'//name)
        call h%attr_string('/injury/'//name, 'description', description)
        call scalar(h, '/injury/'//name//'/value', [v], '1', description)
        call scalar(h, '/injury/'//name//'/t_start', [t1], 's', 'start of the window')
        call scalar(h, '/injury/'//name//'/t_end', [t2], 's', 'end of the window')
    end subroutine window
    subroutine peak(h, name, description, v, t, units)
        type(h5_file_t), intent(inout) :: h
        character(len=*), intent(in) :: name, description, units
        real(wp), intent(in) :: v, t
        call h%group('/injury/'//name)
        call h%attr_string('/injury/'//name, 'description', description)
        call scalar(h, '/injury/'//name//'/value', [v], units, description)
        call scalar(h, '/injury/'//name//'/time', [t], 's', 'time of the peak')
    end subroutine peak
    subroutine frame(h, name, axes, direction)
        type(h5_file_t), intent(inout) :: h
        character(len=*), intent(in) :: name, axes, direction
        call h%attr_string('/injury/'//name, 'frame', axes)
        call h%attr_string('/injury/'//name, 'direction', direction)
    end subroutine frame
    subroutine missing(h, name, source, note)
        type(h5_file_t), intent(inout) :: h
        character(len=*), intent(in) :: name, source, note
        call h%group('/injury/'//name)
        call h%attr_string('/injury/'//name, 'source', source)
        call h%attr_string('/injury/'//name, 'note', note)
    end subroutine missing
    subroutine series(h, name, v, dims, units, description)
        type(h5_file_t), intent(inout) :: h
        character(len=*), intent(in) :: name, units, description
        real(wp), intent(in) :: v(*)
        integer, intent(in) :: dims(:)
        call h%write_real('/injury/history/'//name, v, dims)
        call h%attr_string('/injury/history/'//name, 'units', units)
        call h%attr_string('/injury/history/'//name, 'description', description)
    end subroutine series

end module hn_results
