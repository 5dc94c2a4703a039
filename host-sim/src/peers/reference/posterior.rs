//! The reference's posterior: the kept children materialised into hypotheses over shared tracks, merged when
//! identical, and the events of an association.

use super::*;

impl<M, G, const S: usize, const D: usize, const B: usize> ReferenceTracker<M, G, S, D, B>
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D> + Clone,
{
    /// Turns the kept children, best first, into hypotheses over shared tracks, merging identical ones,
    /// until the posterior's share is used.
    pub(super) fn materialise(
        &self,
        tables: &Tables<G, S, D>,
        children: &ChildBuffer,
        measurements: &[SVector<f64, D>],
    ) -> Result<Posterior<S>, ReferenceError> {
        let mut order: Vec<u32> = (0..children.heads.len() as u32).collect();
        // Best first; ties keep the enumeration order.
        order.sort_unstable_by(|&a, &b| {
            let (x, y) = (&children.heads[a as usize], &children.heads[b as usize]);
            y.log_weight.total_cmp(&x.log_weight).then(a.cmp(&b))
        });
        let mut posterior = Posterior::new(self.next_label, self.shares.posterior);
        let mut sources: Vec<TrackKey> = vec![];
        // Σ w over the kept children, and per row and per pool cell the part of it that takes the row or
        // gives birth in the cell, relative to the best child (docs/maths.md §5.8).
        let (mut mass, mut taken, mut born) = (0.0, vec![0.0; tables.rows], vec![0.0; self.pool.cells().len()]);
        let best = order.first().map_or(0.0, |&i| children.heads[i as usize].log_weight);
        for index in order {
            self.sources(tables, children, index as usize, &mut sources);
            let head = &children.heads[index as usize];
            if !posterior.add(self, tables, measurements, head.log_weight, &sources)? {
                posterior.truncated = true;
                break;
            }
            let weight = (head.log_weight - best).exp();
            mass += weight;
            for &(is_birth, source, row, _) in &sources {
                if row == CLUTTER {
                    continue;
                }
                taken[row as usize] += weight;
                if is_birth && let Some(pool_cell) = tables.scan.cells[source as usize].2 {
                    born[pool_cell] += weight;
                }
            }
        }
        posterior.unexplained = taken.iter().map(|t| 1.0 - t / mass).collect();
        posterior.born = born.iter().map(|b| b / mass).collect();
        posterior.normalise();
        Ok(posterior)
    }

    /// The track keys of child `index`: its parent's surviving objects and its birth, with their rows.
    fn sources(&self, tables: &Tables<G, S, D>, children: &ChildBuffer, index: usize, sources: &mut Vec<TrackKey>) {
        let head = &children.heads[index];
        let row_of = children.rows_of(index);
        sources.clear();
        let mut column = 0;
        for (position, &track) in self.members(&self.hypotheses[head.parent as usize]).iter().enumerate() {
            let predicted = &tables.predicted[tables.slot[track as usize] as usize];
            if predicted.lost {
                continue;
            }
            let row = if predicted.in_view {
                column += 1;
                row_of[column - 1]
            } else {
                CLUTTER
            };
            if head.event != (Event::Death { object: position as u16 }) {
                sources.push((false, track, row, false));
            }
        }
        // Independent births, in the order of the rows they take (as the core makes their labels).
        let first_birth = sources.len();
        for (&cell, &row) in tables.birth_columns.iter().zip(&row_of[column..]) {
            if row != CLUTTER {
                sources.push((true, cell as u32, row, false));
            }
        }
        sources[first_birth..].sort_unstable_by_key(|&(_, _, row, _)| row);
        if let Event::Birth { cell } = head.event {
            let row = if tables.scan.births[cell as usize].1 { row_of[column] } else { CLUTTER };
            sources.push((true, u32::from(cell), row, false));
        }
        // A birth takes its candidate's label L (docs/maths.md §5.8, "One label per candidate") unless the
        // parent holds L or an earlier birth of the child took it; L is a label given before this scan.
        let parent = self.members(&self.hypotheses[head.parent as usize]);
        let held = |label: u32| parent.iter().any(|&t| self.tracks[t as usize].label == label);
        let mut taken: Vec<u32> = vec![];
        for key in &mut sources[first_birth..] {
            if let Some(label) = candidate(&self.pool, tables, key.1).and_then(|(_, label)| label)
                && label < self.next_label
                && !held(label)
                && !taken.contains(&label)
            {
                taken.push(label);
                key.3 = true;
            }
        }
    }

    /// The hypotheses, best first: each one's normalised log-weight and its tracks (label and Gaussian)
    /// in label order.
    pub fn posterior(&self) -> Vec<(f64, Vec<LabelledState<S>>)> {
        let track = |&t: &u32| {
            let track = &self.tracks[t as usize];
            (TrackLabel(track.label), track.state)
        };
        self.hypotheses.iter().map(|h| (h.log_weight, self.members(h).iter().map(track).collect())).collect()
    }
}

/// The candidate (pool group) of birth cell `cell` and the label of its first birth, for a pool cell.
fn candidate<G, const S: usize, const D: usize, const B: usize>(
    pool: &BirthPool<f64, S, B>,
    tables: &Tables<G, S, D>,
    cell: u32,
) -> Option<(u32, Option<u32>)> {
    let pooled = &pool.cells()[tables.scan.cells[cell as usize].2?];
    Some((pooled.group, pooled.label.map(|label| label.0)))
}

/// The events of a parent with `in_view` objects in view, each with its child's objects in view.
pub(super) fn events<const D: usize>(
    weights: &WeightModel<f64>,
    births: &[(Innovation<f64, D>, bool)],
    in_view: usize,
    columns: &[(usize, usize)],
) -> Vec<(Event, usize)> {
    let mut events = vec![(Event::None, in_view)];
    // Independent births are columns of every event's matrix, not events.
    if weights.births_possible() && !weights.independent_births() {
        for (cell, (_, detectable)) in births.iter().enumerate() {
            if *detectable || !weights.birth_required() {
                events.push((Event::Birth { cell: cell as u16 }, in_view + usize::from(*detectable)));
            }
        }
    }
    if weights.deaths_possible() {
        for &(position, _) in columns {
            events.push((Event::Death { object: position as u16 }, in_view - 1));
        }
    }
    events
}

/// The posterior being built from the kept children.
pub(super) struct Posterior<const S: usize> {
    pub(super) tracks: Vec<Track<S>>,
    pub(super) hypotheses: Vec<Hypothesis>,
    pub(super) objects: Vec<u32>,
    pub(super) next_label: u32,
    /// Shared tracks by origin.
    keys: HashMap<TrackKey, u32>,
    /// One label per new object: per measurement for detected births, per cell for undetected ones.
    birth_labels: HashMap<(bool, u32), u32>,
    /// First hypothesis by hash of its tracks, and the next one with the same hash.
    by_hash: HashMap<u64, u32>,
    same_hash: Vec<u32>,
    bytes: usize,
    share: usize,
    pub(super) truncated: bool,
    pub(super) log_mass: f64,
    /// Per measurement, r_U: the kept children's weight that leaves it to clutter (measured births).
    pub(super) unexplained: Vec<f64>,
    /// Per pool cell, the kept children's weight in which it gives birth.
    pub(super) born: Vec<f64>,
    /// The candidates without a label that gave a birth, with the label of the first (best child first).
    pub(super) candidate_labels: Vec<(u32, TrackLabel)>,
    /// Per measurement, the label of the object born from it in the best kept child that gave it one.
    pub(super) row_labels: Vec<Option<TrackLabel>>,
}

impl<const S: usize> Posterior<S> {
    fn new(next_label: u32, share: usize) -> Self {
        Self {
            tracks: vec![],
            hypotheses: vec![],
            objects: vec![],
            next_label,
            keys: HashMap::new(),
            birth_labels: HashMap::new(),
            by_hash: HashMap::new(),
            same_hash: vec![],
            bytes: 0,
            share,
            truncated: false,
            log_mass: f64::NEG_INFINITY,
            unexplained: vec![],
            born: vec![],
            candidate_labels: vec![],
            row_labels: vec![],
        }
    }

    /// Adds a child of weight `log_weight` with tracks from `sources`; `false` (nothing added) when its
    /// new tracks and hypothesis would not fit the share.
    fn add<M, G: MeasurementModel<f64, S, D>, const D: usize, const B: usize>(
        &mut self,
        tracker: &ReferenceTracker<M, G, S, D, B>,
        tables: &Tables<G, S, D>,
        measurements: &[SVector<f64, D>],
        log_weight: f64,
        sources: &[TrackKey],
    ) -> Result<bool, ReferenceError> {
        let new = sources.iter().filter(|k| !self.keys.contains_key(k)).count();
        let cost = new * track_bytes::<S>() + HYPOTHESIS_BYTES + sources.len() * OBJECT_BYTES;
        if self.bytes + cost > self.share && !self.hypotheses.is_empty() {
            return Ok(false);
        }
        let start = self.objects.len();
        for &key in sources {
            let index = match self.keys.get(&key) {
                Some(&index) => index,
                None => self.new_track(tracker, tables, measurements, key)?,
            };
            self.objects.push(index);
        }
        self.objects[start..].sort_by_key(|&i| self.tracks[i as usize].label);
        let mut hasher = DefaultHasher::new();
        self.objects[start..].hash(&mut hasher);
        let hash = hasher.finish();
        let mut candidate = self.by_hash.get(&hash).copied();
        while let Some(existing) = candidate {
            let h = self.hypotheses[existing as usize];
            if self.objects[h.start..h.start + h.len as usize] == self.objects[start..] {
                self.objects.truncate(start);
                let h = &mut self.hypotheses[existing as usize];
                h.log_weight = log_add(h.log_weight, log_weight);
                self.bytes += new * track_bytes::<S>();
                return Ok(true);
            }
            candidate = Some(self.same_hash[existing as usize]).filter(|&n| n != u32::MAX);
        }
        let index = self.hypotheses.len() as u32;
        self.same_hash.push(self.by_hash.insert(hash, index).unwrap_or(u32::MAX));
        self.hypotheses.push(Hypothesis { log_weight, start, len: sources.len() as u32 });
        self.bytes += cost;
        Ok(true)
    }

    /// Makes the track of `key`: the old track predicted, or the birth cell's, updated with its row.
    fn new_track<M, G: MeasurementModel<f64, S, D>, const D: usize, const B: usize>(
        &mut self,
        tracker: &ReferenceTracker<M, G, S, D, B>,
        tables: &Tables<G, S, D>,
        measurements: &[SVector<f64, D>],
        key: TrackKey,
    ) -> Result<u32, ReferenceError> {
        let (is_birth, source, row, inherits) = key;
        let (label, prior, innovation, unseen) = if is_birth {
            let candidate = candidate(&tracker.pool, tables, source);
            let birth_key = if row == CLUTTER { (false, source) } else { (true, row) };
            let next_label = &mut self.next_label;
            let label = match candidate {
                Some((_, Some(label))) if inherits => label,
                _ => *self.birth_labels.entry(birth_key).or_insert_with(|| {
                    *next_label += 1;
                    *next_label - 1
                }),
            };
            if let Some((group, None)) = candidate
                && !self.candidate_labels.iter().any(|&(other, _)| other == group)
            {
                self.candidate_labels.push((group, TrackLabel(label)));
            }
            if row != CLUTTER {
                let row = row as usize;
                if self.row_labels.len() <= row {
                    self.row_labels.resize(row + 1, None);
                }
                self.row_labels[row].get_or_insert(TrackLabel(label));
            }
            (label, tables.scan.cells[source as usize].0, tables.scan.births[source as usize].0, 0)
        } else {
            let p = &tables.predicted[tables.slot[source as usize] as usize];
            (tracker.tracks[source as usize].label, p.state, p.innovation, p.unseen)
        };
        let state = if row == CLUTTER {
            prior
        } else {
            ekf::update(&tables.scan.placed.model, &prior, &innovation, &measurements[row as usize])
                .map_err(|error| StepError::Numerical { label: TrackLabel(label), error })?
        };
        self.tracks.push(Track { label, state, unseen });
        let index = (self.tracks.len() - 1) as u32;
        self.keys.insert(key, index);
        Ok(index)
    }

    /// Normalises the weights and sorts the hypotheses best first (ties: first made first).
    fn normalise(&mut self) {
        self.keys = HashMap::new();
        self.by_hash = HashMap::new();
        self.same_hash = vec![];
        let mut kept = LogSumExp::new();
        for h in &self.hypotheses {
            kept.add(h.log_weight);
        }
        self.log_mass = kept.value();
        for h in &mut self.hypotheses {
            h.log_weight -= self.log_mass;
        }
        self.hypotheses.sort_by(|a, b| b.log_weight.total_cmp(&a.log_weight));
    }
}
