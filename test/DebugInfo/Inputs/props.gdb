set pagination off
set confirm off
break props.bs:16
run
info locals
print v
print w.x()
print w.y()
print odo.laps()
print odo.moving()
print/r v
print odo
bt
ptype odo
kill
