!> The PRINT card (docs/deck-format.md): which channel groups the listing
!! prints as time-history tables besides the main ones.
!!
!!   PRINT     F1-F7 one keyword each: ALL, HEAD, HEAD3D, T1, OC, LOADCELLS,
!!             JOINTS, DISCS, LIGAMENTS, MUSCLES, LIMITS, NZSPRINGS, ENERGY
!!
!! The card repeats; its keywords add up. The main groups (head
!! kinematics, T1, the upper-neck loads and the load cells: `main` below)
!! are printed without the card; ALL prints every listed channel in one
!! table per group, the listing of earlier versions. A keyword stands for
!! channel groups (hn_channels' and the element families' group names) by
!! name or by a prefix ending in '*'; `print_keyword` finds a group's
!! keyword, `print_selects` says whether a selection prints a group.
module hn_print_card
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t
    use hn_deck_state, only: card_t
    implicit none
    private

    public :: print_cards, print_selects, print_keyword, print_title, print_keywords

    integer, parameter, public :: keyword_len = 10   !! longest PRINT keyword (a field)

    !> One keyword's channel groups: a group name or a prefix ending in '*'.
    type :: print_group_t
        character(len=keyword_len) :: keyword = ''
        character(len=16) :: pattern = ''
        character(len=40) :: title = ''      !! how a table names the keyword's channels
        logical :: main = .false.            !! printed without a PRINT card
    end type print_group_t

    !> The keywords and their groups, in the order of the channels (hn_channels).
    type(print_group_t), parameter :: groups(*) = [ &
        print_group_t('HEAD', 'HEAD', 'HEAD KINEMATICS', .true.), &
        print_group_t('HEAD3D', 'HEAD 3D', 'HEAD 3-D KINEMATICS', .false.), &
        print_group_t('T1', 'T1', 'T1 MOTION', .true.), &
        print_group_t('OC', 'OC LOADS', 'UPPER-NECK (OC) LOADS', .true.), &
        print_group_t('LOADCELLS', 'LOADCELL *', 'LOAD CELLS', .true.), &
        print_group_t('LOADCELLS', 'J211 *', 'LOAD CELLS', .true.), &
        print_group_t('JOINTS', 'JOINTS *', 'JOINT ROTATIONS', .false.), &
        print_group_t('DISCS', 'DISC *', 'DISC LOADS', .false.), &
        print_group_t('LIGAMENTS', 'LIGAMENTS', 'LIGAMENT TENSIONS', .false.), &
        print_group_t('MUSCLES', 'MUSCLE*', 'MUSCLE TENSIONS AND ACTIVATIONS', .false.), &
        print_group_t('LIMITS', 'JOINT LIMITS', 'JOINT-LIMIT LOADS', .false.), &
        print_group_t('NZSPRINGS', 'NZ SPRINGS', 'NEUTRAL-ZONE SPRING MOMENTS', .false.), &
        print_group_t('CONTACTS', 'CONTACT *', 'CONTACT FORCES AND DEPTHS', .false.), &
        print_group_t('ENERGY', 'ENERGY', 'ENERGY TERMS', .false.)]

contains

    !> The keywords a PRINT field takes: ALL, then each group keyword once.
    pure function print_keywords() result(k)
        character(len=keyword_len), allocatable :: k(:)
        integer :: j
        k = [character(len=keyword_len) :: 'ALL']
        do j = 1, size(groups)
            if (.not. any(k == groups(j)%keyword)) k = [character(len=keyword_len) :: k, groups(j)%keyword]
        end do
    end function print_keywords

    !> Every PRINT card of the deck into cs%print_groups (their keywords, in
    !! deck order); an unknown keyword or a card without one is a located
    !! error (rd%fail).
    subroutine print_cards(rd, cards, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), intent(in) :: cards(:)      !! the deck's cards with their continuation cards (group_cards)
        type(case_t), intent(inout) :: cs         !! the run case: print_groups set
        character(len=keyword_len) :: v
        integer :: k, f, i, n
        cs%print_groups = [character(len=keyword_len) ::]
        do k = 1, size(cards)
            if (rd%failed()) return
            if (cards(k)%key /= 'PRINT') cycle
            i = cards(k)%first
            n = 0
            do f = 1, 7
                if (rd%is_blank(i, f)) cycle
                call rd%choice(i, f, 'channel group', print_keywords(), v)
                if (rd%failed()) return
                cs%print_groups = [character(len=keyword_len) :: cs%print_groups, v]
                n = n + 1
            end do
            if (n == 0) then
                call rd%fail(rd%context(i, 1, 'channel group')//': found a PRINT card without a keyword; '// &
                             'expected ALL or channel groups in F1-F7 (docs/deck-format.md, PRINT)')
                return
            end if
        end do
    end subroutine print_cards

    !> Place in the keyword table of the keyword that stands for channel
    !! group `group`, 0 when none does.
    pure integer function group_entry(group) result(j)
        character(len=*), intent(in) :: group
        integer :: n
        do j = 1, size(groups)
            n = len_trim(groups(j)%pattern)
            if (groups(j)%pattern(n:n) == '*') then
                if (n == 1) return
                if (len(group) >= n - 1) then
                    if (group(1:n - 1) == groups(j)%pattern(1:n - 1)) return
                end if
            else if (group == groups(j)%pattern) then
                return
            end if
        end do
        j = 0
    end function group_entry

    !> The PRINT keyword of channel group `group` ('' when no keyword but ALL selects it).
    pure function print_keyword(group) result(k)
        character(len=*), intent(in) :: group   !! a channel group (hn_channels)
        character(len=keyword_len) :: k
        integer :: j
        j = group_entry(group)
        k = ''
        if (j > 0) k = groups(j)%keyword
    end function print_keyword

    !> How the listing's tables name the channels of group `group` (the group itself when no keyword has it).
    pure function print_title(group) result(s)
        character(len=*), intent(in) :: group   !! a channel group (hn_channels)
        character(len=40) :: s
        integer :: j
        j = group_entry(group)
        s = group
        if (j > 0) s = groups(j)%title
    end function print_title

    !> Whether the listing prints the time history of channel group `group`
    !! under the PRINT keywords `selected` (none: the main groups only).
    pure logical function print_selects(selected, group) result(yes)
        character(len=*), intent(in) :: selected(:)   !! the PRINT cards' keywords
        character(len=*), intent(in) :: group         !! a channel group (hn_channels)
        integer :: j
        yes = any(selected == 'ALL')
        j = group_entry(group)
        if (j == 0) return
        yes = yes .or. groups(j)%main .or. any(selected == groups(j)%keyword)
    end function print_selects

end module hn_print_card
