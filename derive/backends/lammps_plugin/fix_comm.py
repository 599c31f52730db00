"""The forward and reverse communication of the LAMMPS fix ``fricgen/exact/<law>`` (C++, the tail of fix_source's
template): the owners' velocities and spins to their ghost copies before a phase, and the touched ghost copies'
to their owners after it (a copy that was not touched carries a 0 flag and changes nothing); at a neighbour-list
build, the pairs a rank lists for a ghost of lower ID to that atom's owner (send_pairs)."""

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

// The pairs of sent to the owners of their ghost copies, 6 IDs per copy and round, until no rank has one left;
// a pair that arrives at a ghost copy (a corner, whose owner is reached through another rank) goes on next round.
// received: the pairs that arrived at owned atoms.
void ${fix_cls}::send_pairs()
{
  const int nlocal = atom->nlocal, nall = atom->nlocal + atom->nghost;
  std::vector<std::pair<int, tagint>> arrived, rest;
  while (true) {
    int left = sent.empty() ? 0 : 1, any;
    MPI_Allreduce(&left, &any, 1, MPI_INT, MPI_MAX, world);
    if (!any) break;
    std::sort(sent.begin(), sent.end());
    next_sent.assign(nall, 0);
    end_sent.assign(nall, 0);
    for (size_t s = sent.size(); s-- > 0;) next_sent[sent[s].first] = static_cast<int>(s);
    for (size_t s = 0; s < sent.size(); s++) end_sent[sent[s].first] = static_cast<int>(s) + 1;
    received.clear();
    sending = true;
    comm->reverse_comm(this);
    sending = false;
    rest.clear();
    for (int g = nlocal; g < nall; g++)    // what did not fit this round
      for (int s = next_sent[g]; s < end_sent[g]; s++) rest.push_back(sent[s]);
    for (const std::pair<int, tagint> &got : received) (got.first < nlocal ? arrived : rest).push_back(got);
    sent.swap(rest);
  }
  received.swap(arrived);
}

int ${fix_cls}::pack_reverse_comm(int n, int first, double *buf)
{
  if (sending) {
    int m = 0;
    for (int g = first; g < first + n; g++, m += 7) {
      int k = 0;
      for (; k < 6 && next_sent[g] < end_sent[g]; k++) buf[m + 1 + k] = static_cast<double>(sent[next_sent[g]++].second);
      buf[m] = k;
      for (int rest = k; rest < 6; rest++) buf[m + 1 + rest] = 0.0;
    }
    return m;
  }
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
  if (sending) {
    for (int s = 0, m = 0; s < n; s++, m += 7)
      for (int k = 0; k < static_cast<int>(buf[m]); k++) received.push_back({receive[s], static_cast<tagint>(buf[m + 1 + k])});
    return;
  }
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
