// Fly: the scenario's YAML flown by the server into the output folder (one run at a time), its
// progress polled, a cancel, then the folder's report page in a pane over the map.
import * as api from './api.js';

export class FlyControl {
  constructor({ flyButton, cancelButton, progress, status, reportPane, reportFrame, closeButton, yaml, onProblem }) {
    Object.assign(this, { flyButton, cancelButton, progress, status, reportPane, reportFrame, yaml, onProblem });
    flyButton.addEventListener('click', () => this.fly());
    cancelButton.addEventListener('click', () => api.cancel());
    closeButton.addEventListener('click', () => { reportPane.hidden = true; });
  }

  async fly() {
    const answer = await api.fly(this.yaml());
    if (!answer.ok) {
      this.onProblem(answer.problem);
      return;
    }
    this.flyButton.disabled = true;
    this.cancelButton.hidden = false;
    this.progress.hidden = false;
    this.poll();
  }

  async poll() {
    const run = await api.runStatus();
    const total = Math.max(1, run.frames_total);
    this.progress.max = total;
    this.progress.value = run.frames_done;
    this.status.textContent = `${run.state}: ${run.frames_done} / ${run.frames_total} frames`;
    if (['building', 'flying', 'report'].includes(run.state)) {
      setTimeout(() => this.poll(), 250);
      return;
    }
    this.flyButton.disabled = false;
    this.cancelButton.hidden = true;
    this.progress.hidden = true;
    if (run.state === 'done') {
      this.status.textContent = `flown: ${run.frames_total} frames into ${run.out}`;
      this.reportFrame.src = `/out/report.html?run=${Date.now()}`;
      this.reportPane.hidden = false;
    } else if (run.state === 'failed') {
      this.onProblem({ message: run.error });
    }
  }
}
