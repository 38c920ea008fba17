set pagination off
set confirm off
break dw::noteKick
run
bt
frame 3
info args
info locals
print *__bs_state->input
print __bs_state->kick.kick
print __bs_state->headers.kick
print __bs_state->kick.main.mode
break kick.bs:16
continue
info locals
bt
delete
break kick::kick
continue
print power
print aim
print __bs_state->kick.kick.kicked
next
next
next
kill
