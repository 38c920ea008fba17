set pagination off
set confirm off
break dw::noteKick
run
bt
frame 3
info args
info locals
print *state->input
print state->kick.kick
print state->headers.kick
print state->kick.main.mode
break kick.bs:16
continue
info locals
bt
delete
break kick::kick
continue
print power
print aim
print state->kick.kick.kicked
next
next
next
kill
