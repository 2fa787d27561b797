!> The scene cards of a deck: SCENE SAGITTAL and MERGE, which reduce the
!! model to what the scene needs (`scene_cards`, between the body cards and
!! the building of the tree).
module hn_deck_scene
    use hn_kinds, only: wp, msglen
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t
    use hn_scene, only: merge_bodies, lock_sagittal
    use hn_deck_state, only: card_t, body_map_t, single, add_scene_note, body_ref
    implicit none
    private

    public :: scene_cards

contains

    !> SCENE SAGITTAL and MERGE survivor absorbed...: reduce the model to what
    !! the scene needs; notes for the listing.
    subroutine scene_cards(rd, cards, cs, bnames, bmap)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        character(len=10), intent(in) :: bnames(:)  !! the names of the deck's bodies, in deck order
        type(body_map_t), intent(inout) :: bmap  !! where each deck body went (MERGE), what locked its coordinates
        integer :: ic, k, i, f, nabs, surv, kk, stat
        integer, allocatable :: absorbed(:), new_index(:)
        real(wp), allocatable :: shift(:, :)
        character(len=10) :: s
        character(len=msglen) :: msg
        character(len=100) :: note
        ic = single(cards, 'SCENE')
        if (ic > 0) then
            call rd%choice(cards(ic)%first, 1, 'scene', [character(len=8) :: 'SAGITTAL', 'FULL'], s)
            if (rd%failed()) return
            if (s == 'SAGITTAL') then
                call lock_sagittal(cs%model%tree)
                do f = 2, 6, 2
                    where (bmap%locked_by(f, :) == 0) bmap%locked_by(f, :) = cards(ic)%first
                end do
                call add_note('SCENE SAGITTAL: TY, RX, RZ OF EVERY BODY LOCKED AT NEUTRAL')
            end if
        end if
        do k = 1, size(cards)
            if (cards(k)%key /= 'MERGE') cycle
            i = cards(k)%first
            surv = body_ref(rd, i, 1, 'surviving body', bnames, .false.)
            allocate (absorbed(0))
            do f = 2, 7
                if (rd%is_blank(i, f)) cycle
                kk = body_ref(rd, i, f, 'absorbed body', bnames, .false.)
                if (rd%failed()) return
                absorbed = [absorbed, kk]
            end do
            if (rd%failed()) return
            if (size(absorbed) == 0) then
                call rd%fail(rd%where(i)//', columns 21-80 (MERGE card): found no body to absorb; expected 1 to 6')
                return
            end if
            ! bodies already merged are addressed through their survivor
            surv = bmap%new(surv)
            absorbed = bmap%new(absorbed)
            if (any(absorbed == surv)) then
                call rd%fail(rd%where(i)//' (MERGE card): a body cannot absorb itself (or one already merged into it)')
                return
            end if
            allocate (new_index(cs%model%tree%nbody), shift(3, cs%model%tree%nbody))
            call merge_bodies(cs%model%tree, surv, absorbed, new_index, shift, stat, msg)
            if (stat /= 0) then
                call rd%fail(rd%where(i)//' (MERGE card): '//trim(msg))
                return
            end if
            ! compose with the map so far
            do kk = 1, size(bmap%new)
                bmap%shift(:, kk) = bmap%shift(:, kk) + shift(:, bmap%new(kk))
                if (any(absorbed == bmap%new(kk))) bmap%merged_by(kk) = i
                bmap%new(kk) = new_index(bmap%new(kk))
            end do
            nabs = size(absorbed)
            write (note, '(a,i0,3a)') 'MERGE: ', nabs, ' BODIES ABSORBED INTO ', &
                trim(cs%model%tree%name(new_index(surv))), ' (MASS, INERTIA BY THE PARALLEL-AXIS THEOREM)'
            call add_note(note)
            deallocate (absorbed, new_index, shift)
        end do
    contains
        subroutine add_note(text)
            character(len=*), intent(in) :: text
            call add_scene_note(cs, text)
        end subroutine add_note
    end subroutine scene_cards

end module hn_deck_scene
