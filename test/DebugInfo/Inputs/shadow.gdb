set pagination off
set confirm off
break sw::note
run
bt
frame 3
info args
print __bs_state->cycle
print __bs_state->shadow.patrol.state
frame 4
info locals
print state
print pos
print __bs_state->shadow.patrol
print __bs_state->shadow.patrol.__bs_state
print __bs_state->headers.patrol
continue
frame 4
print state
print __bs_state->cycle
print __bs_state->shadow.patrol.__bs_state
kill
