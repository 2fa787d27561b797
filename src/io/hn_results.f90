!> The HDF5 result file of a run: model tables, every channel at the
!! sampling interval, body positions and orientations, coordinates, and run
!! status. Samples are buffered and written in blocks, and the file is
!! flushed at every block, so a stopped run keeps what it has computed.
!! Layout in docs/output-format.md.
module hn_results
    use hn_kinds, only: wp, zero, msglen
    use hn_case, only: case_t
    use hn_channels, only: channel_set_t
    use hn_dynamics, only: dyn_workspace_t
    use hn_tree, only: dof_label
    use hn_h5, only: h5_file_t
    use hn_dump, only: dump_open
    use hn_assessment, only: assessment_t
    use hn_results_model, only: write_element_tables
    implicit none
    private

    public :: results_t

    integer, parameter :: block = 200

    !> Result file and its sample buffers.
    type :: results_t
        type(h5_file_t) :: h5
        logical :: active = .false.
        integer :: nbuf = 0, nwritten = 0
        real(wp), allocatable :: time(:), chan(:, :), pos(:, :, :), rot(:, :, :, :), x(:, :), xd(:, :)
    contains
        procedure :: open => results_open
        procedure :: sample => results_sample
        procedure :: flush => results_flush
        procedure :: close => results_close
        procedure :: criteria => results_criteria
    end type results_t

contains

    !> Create the file and write the model tables.
    subroutine results_open(me, cs, ch, fname, code_version, stat, errmsg)
        class(results_t), intent(inout) :: me
        type(case_t), intent(in) :: cs
        type(channel_set_t), intent(in) :: ch
        character(len=*), intent(in) :: fname, code_version
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        integer :: nb, n, k, j
        character(len=:), allocatable :: deck, names
        call me%h5%create(fname, stat, errmsg)
        if (stat /= 0) return
        me%active = .true.
        nb = cs%model%tree%nbody
        n = cs%model%tree%ndof
        deck = ''
        do k = 1, size(cs%deck)
            deck = deck//cs%deck(k)%text//new_line('a')
        end do
        call me%h5%attr_string('/', 'code', 'HHNECK '//code_version)
        call me%h5%attr_string('/', 'title', trim(cs%model%title))
        call me%h5%attr_string('/', 'deck', deck)
        call me%h5%attr_string('/', 'status', 'running')
        call me%h5%group('/model')
        names = ''
        do k = 1, nb
            names = names//trim(cs%model%tree%name(k))//' '
        end do
        call me%h5%attr_string('/model', 'bodies', trim(names))
        names = ''
        do j = 1, n
            names = names//trim(dof_label(cs%model%tree, j))//' '
        end do
        call me%h5%attr_string('/model', 'coordinates', trim(names))
        call me%h5%write_int('/model/parent', cs%model%tree%parent, [nb])
        call me%h5%write_real('/model/mass', cs%model%tree%mass, [nb])
        call me%h5%write_real('/model/inertia', cs%model%tree%inertia, [3, 3, nb])
        call me%h5%write_real('/model/joint_in_parent', cs%model%tree%joint_parent, [3, nb])
        call me%h5%write_real('/model/joint_in_body', cs%model%tree%joint_child, [3, nb])
        call me%h5%write_int('/model/prescribed', merge(1, 0, cs%model%prescribed), [n])
        call write_element_tables(me%h5, cs%model)
        call me%h5%group('/channels')
        do k = 1, ch%n
            call me%h5%series('/channels/'//trim(ch%name(k)), [integer ::])
            call me%h5%attr_string('/channels/'//trim(ch%name(k)), 'units', trim(ch%units(k)))
        end do
        call me%h5%series('/time', [integer ::])
        call me%h5%attr_string('/time', 'units', 's')
        call me%h5%group('/bodies')
        call me%h5%series('/bodies/position', [3, nb])
        call me%h5%series('/bodies/rotation', [3, 3, nb])
        call me%h5%group('/coordinates')
        call me%h5%series('/coordinates/x', [n])
        call me%h5%series('/coordinates/xd', [n])
        if (size(cs%dump_times) > 0) call dump_open(me%h5, cs%model)
        allocate (me%time(block), me%chan(block, ch%n), me%pos(3, nb, block), me%rot(3, 3, nb, block))
        allocate (me%x(n, block), me%xd(n, block))
        me%nbuf = 0
    end subroutine results_open

    !> Buffer one sample; writes a block when the buffer is full.
    subroutine results_sample(me, t, ch, ws)
        class(results_t), intent(inout) :: me
        real(wp), intent(in) :: t
        type(channel_set_t), intent(in) :: ch
        type(dyn_workspace_t), intent(in) :: ws
        if (.not. me%active) return
        me%nbuf = me%nbuf + 1
        me%time(me%nbuf) = t
        me%chan(me%nbuf, :) = ch%value
        me%pos(:, :, me%nbuf) = ws%kin%r
        me%rot(:, :, :, me%nbuf) = ws%kin%s
        me%x(:, me%nbuf) = ws%x
        me%xd(:, me%nbuf) = ws%xd
        if (me%nbuf == block) call me%flush(ch)
    end subroutine results_sample

    !> Write the buffered samples and flush the file.
    subroutine results_flush(me, ch)
        class(results_t), intent(inout) :: me
        type(channel_set_t), intent(in) :: ch
        integer :: k, nb
        if (.not. me%active) return
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
        call me%h5%flush()
    end subroutine results_flush

    !> Write what is left, the status ('complete' or 'incomplete') and
    !! message, close, and give the file its final name. Only a run that
    !! dies without reaching this point leaves the temporary file.
    subroutine results_close(me, ch, status, message, stat, errmsg)
        class(results_t), intent(inout) :: me
        type(channel_set_t), intent(in) :: ch
        character(len=*), intent(in) :: status, message
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        stat = 0; errmsg = ''
        if (.not. me%active) return
        call me%flush(ch)
        call me%h5%attr_string('/', 'status', status)
        call me%h5%attr_string('/', 'message', message)
        call me%h5%close(.true., stat, errmsg)
        me%active = .false.
    end subroutine results_close

    !> Group /injury: criteria values as attributes, their time histories
    !! (same time base as /time) as datasets.
    subroutine results_criteria(me, a)
        class(results_t), intent(inout) :: me
        type(assessment_t), intent(in) :: a
        integer :: n
        real(wp), allocatable :: modes(:, :)
        if (.not. me%active) return
        call me%h5%group('/injury')
        if (.not. a%computed) then
            call me%h5%attr_string('/injury', 'note', trim(a%note))
            return
        end if
        n = size(a%head_ar)
        call me%h5%attr_real('/injury', 'hic15', [a%hic15, a%hic15_t1, a%hic15_t2])
        call me%h5%attr_real('/injury', 'hic36', [a%hic36, a%hic36_t1, a%hic36_t2])
        call me%h5%attr_real('/injury', 'nij_max', a%nij_max)
        call me%h5%attr_real('/injury', 'nij_time', a%nij_time)
        call me%h5%attr_real('/injury', 'nic', [a%nic_max, a%nic_time])
        call me%h5%attr_real('/injury', 'tension', [a%tension, a%tension_t])
        call me%h5%attr_real('/injury', 'compression', [a%compression, a%compression_t])
        call me%h5%attr_real('/injury', 'shear', [a%shear, a%shear_t])
        call me%h5%attr_real('/injury', 'flexion_moment', [a%flexion, a%flexion_t])
        call me%h5%attr_real('/injury', 'extension_moment', [a%extension, a%extension_t])
        call me%h5%write_real('/injury/head_ar_cfc1000', a%head_ar, [n])
        modes = transpose(a%nij_t)          ! (4, n): h5py reads (n, 4), time first
        call me%h5%write_real('/injury/nij', modes, [4, n])
        call me%h5%attr_string('/injury/nij', 'columns', 'NTE NTF NCE NCF')
        call me%h5%write_real('/injury/nic', a%nic_t, [n])
        call me%h5%write_real('/injury/oc_fx_cfc600', a%fx, [n])
        call me%h5%write_real('/injury/oc_fz_cfc600', a%fz, [n])
        call me%h5%write_real('/injury/oc_my_cfc600', a%my, [n])
    end subroutine results_criteria

end module hn_results
