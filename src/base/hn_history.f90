!> A growing table of rows of m reals (a run's listing rows, its criteria
!! channels) whose memory does not grow with the run: the first rows stay
!! in memory, later ones go to an unformatted scratch file and are read back
!! on request. A long run therefore holds a fixed amount of history in
!! memory, whatever its length.
module hn_history
    use hn_kinds, only: wp, i8
    implicit none
    private

    public :: history_t

    integer, parameter :: default_bytes = 2*1024*1024   !! memory kept before spilling

    !> Rows of m values.
    type :: history_t
        integer :: m = 0                   !! values per row
        integer :: n = 0                   !! rows stored
        integer :: cap = 0                 !! rows kept in memory
        integer :: unit = 0                !! scratch file of the rows beyond cap
        logical :: spilled = .false.       !! the scratch file is open
        integer :: stat = 0                !! first I/O error of the scratch file (0: none)
        real(wp), allocatable :: mem(:, :) !! (m, cap) the first rows
    contains
        procedure :: init => history_init
        procedure :: add => history_add
        procedure :: get => history_get
        procedure :: column => history_column
        procedure :: clear => history_clear
    end type history_t

contains

    !> Empty table of rows of m values, at most about `bytes` of them in memory.
    subroutine history_init(me, m, bytes)
        class(history_t), intent(inout) :: me
        integer, intent(in) :: m                  !! values per row
        integer, intent(in), optional :: bytes    !! memory for rows before spilling to disk
        integer :: b
        call me%clear()
        b = default_bytes
        if (present(bytes)) b = bytes
        me%m = m
        me%n = 0
        me%cap = max(16, b/(8*max(m, 1)))
        allocate (me%mem(m, min(me%cap, 1024)))
    end subroutine history_init

    !> Append one row.
    subroutine history_add(me, row)
        class(history_t), intent(inout) :: me
        real(wp), intent(in) :: row(:)   !! m values
        real(wp), allocatable :: tmp(:, :)
        integer :: ios
        me%n = me%n + 1
        if (me%n <= me%cap) then
            if (me%n > size(me%mem, 2)) then
                allocate (tmp(me%m, min(me%cap, 2*size(me%mem, 2))))
                tmp(:, 1:me%n - 1) = me%mem(:, 1:me%n - 1)
                call move_alloc(tmp, me%mem)
            end if
            me%mem(:, me%n) = row
            return
        end if
        if (.not. me%spilled .and. me%stat == 0) then
            open (newunit=me%unit, status='scratch', access='stream', form='unformatted', iostat=ios)
            me%spilled = ios == 0
            me%stat = ios
        end if
        if (me%spilled .and. me%stat == 0) write (me%unit, iostat=me%stat) row
    end subroutine history_add

    !> Row i (1..n); zeros when it could not be read back.
    subroutine history_get(me, i, row)
        class(history_t), intent(in) :: me
        integer, intent(in) :: i              !! row number
        real(wp), intent(out) :: row(:)       !! its m values
        integer(i8) :: pos
        integer :: ios
        row = 0.0_wp
        if (i < 1 .or. i > me%n) return
        if (i <= me%cap) then
            row = me%mem(:, i)
        else if (me%spilled) then
            pos = int(i - me%cap - 1, i8)*int(me%m, i8)*8_i8 + 1_i8
            read (me%unit, pos=pos, iostat=ios) row
        end if
    end subroutine history_get

    !> Column j of every row.
    function history_column(me, j) result(v)
        class(history_t), intent(in) :: me
        integer, intent(in) :: j             !! column (1..m)
        real(wp), allocatable :: v(:)
        real(wp) :: row(me%m)
        integer :: i
        allocate (v(me%n))
        do i = 1, me%n
            if (i <= me%cap) then
                v(i) = me%mem(j, i)
            else
                call me%get(i, row)
                v(i) = row(j)
            end if
        end do
    end function history_column

    !> Forget every row (the scratch file is deleted).
    subroutine history_clear(me)
        class(history_t), intent(inout) :: me
        if (me%spilled) close (me%unit)
        me%spilled = .false.
        me%n = 0
        me%stat = 0
        if (allocated(me%mem)) deallocate (me%mem)
    end subroutine history_clear

end module hn_history
