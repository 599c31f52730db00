"""The forward and reverse communication of the LAMMPS fix ``fricgen/exact/<law>`` (C++, the tail of fix_source's
template): the owners' velocities and spins to their ghost copies before a phase, and the touched ghost copies'
to their owners after it (a copy that was not touched carries a 0 flag and changes nothing)."""

COMMUNICATION = r"""int ${fix_cls}::pack_forward_comm(int n, int *send, double *buf, int, int *)
{
  double **v = atom->v, **omega = atom->omega;
  int m = 0;
  for (int s = 0; s < n; s++) {
    const int i = send[s];
    for (int a = 0; a < 3; a++) buf[m++] = v[i][a];
    for (int a = 0; a < 3; a++) buf[m++] = omega[i][a];
  }
  return m;
}

void ${fix_cls}::unpack_forward_comm(int n, int first, double *buf)
{
  double **v = atom->v, **omega = atom->omega;
  int m = 0;
  for (int i = first; i < first + n; i++) {
    for (int a = 0; a < 3; a++) v[i][a] = buf[m++];
    for (int a = 0; a < 3; a++) omega[i][a] = buf[m++];
  }
}

int ${fix_cls}::pack_reverse_comm(int n, int first, double *buf)
{
  double **v = atom->v, **omega = atom->omega;
  int m = 0;
  for (int i = first; i < first + n; i++) {
    buf[m++] = touched[i] ? 1.0 : 0.0;
    for (int a = 0; a < 3; a++) buf[m++] = v[i][a];
    for (int a = 0; a < 3; a++) buf[m++] = omega[i][a];
  }
  return m;
}

// A touched copy's velocity and spin replace the receiver's (no other rank touched that atom in the phase).
void ${fix_cls}::unpack_reverse_comm(int n, int *receive, double *buf)
{
  double **v = atom->v, **omega = atom->omega;
  int m = 0;
  for (int s = 0; s < n; s++, m += 7) {
    const int j = receive[s];
    if (buf[m] == 0.0) continue;
    for (int a = 0; a < 3; a++) v[j][a] = buf[m + 1 + a];
    for (int a = 0; a < 3; a++) omega[j][a] = buf[m + 4 + a];
    touched[j] = 1;
  }
}
"""
